// run_report.cpp — sizes of a run's outputs (run_report.hpp).
#include "run_report.hpp"

#include <cstdio>

namespace cdyn::app {

namespace fs = std::filesystem;

std::uintmax_t bytes_of(const fs::path& p) {
  std::error_code ec;
  if (fs::is_regular_file(p, ec)) return fs::file_size(p, ec);
  std::uintmax_t total = 0;
  if (!fs::is_directory(p, ec)) return 0;
  for (const auto& e : fs::recursive_directory_iterator(p, ec))
    if (e.is_regular_file(ec)) total += e.file_size(ec);
  return total;
}

nlohmann::ordered_json written_bytes(const fs::path& out) {
  nlohmann::ordered_json j;
  std::uintmax_t total = 0;
  auto add = [&](const char* name, std::uintmax_t bytes) {
    j[name] = bytes;
    total += bytes;
  };
  for (const char* name : {"scene.toml", "history.csv", "contact.csv"})
    if (fs::exists(out / name)) add(name, bytes_of(out / name));
  if (fs::exists(out / "fields.pvd")) add("fields", bytes_of(out / "fields.pvd") + bytes_of(out / "fields"));
  if (fs::exists(out / "checkpoint")) add("checkpoint", bytes_of(out / "checkpoint"));
  j["total"] = total;
  return j;
}

std::string human_bytes(std::uintmax_t bytes) {
  char text[32];
  if (bytes < 1000) {
    std::snprintf(text, sizeof text, "%ju B", bytes);
  } else {
    const char* units[] = {"kB", "MB", "GB", "TB"};
    double x = bytes / 1000.0;
    int u = 0;
    for (; x >= 1000.0 && u < 3; ++u) x /= 1000.0;
    std::snprintf(text, sizeof text, "%.3g %s", x, units[u]);
  }
  return text;
}

}  // namespace cdyn::app
