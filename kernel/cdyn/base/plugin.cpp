// plugin.cpp — dlopen of a plugin's candidate files; see plugin.hpp.
#include "cdyn/base/plugin.hpp"

#include <dlfcn.h>

#include <system_error>

namespace cdyn {

std::filesystem::path beside_installed_program(const std::string& file) {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path().parent_path() / "lib" / "cdyn" / file;
}

const void* open_plugin(const std::vector<std::filesystem::path>& candidates, const char* symbol, int flags,
                        const std::function<bool(const void*)>& matches, std::string& tried,
                        std::filesystem::path* opened) {
  for (const auto& file : candidates) {
    if (file.empty() || !std::filesystem::exists(file)) continue;
    void* handle = dlopen(file.c_str(), flags);
    if (!handle) {
      tried += std::string(tried.empty() ? "" : "; ") + dlerror();
      continue;
    }
    auto entry = reinterpret_cast<const void* (*)()>(dlsym(handle, symbol));
    const void* table = entry ? entry() : nullptr;
    if (!table || !matches(table)) {
      tried += (tried.empty() ? "" : "; ") + file.string() + ": not this cdyn's plugin";
      continue;
    }
    if (opened) *opened = file;
    return table;
  }
  return nullptr;
}

}  // namespace cdyn
