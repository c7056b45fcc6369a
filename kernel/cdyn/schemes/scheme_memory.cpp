// schemes/scheme_memory.cpp — entries of a scheme's memory; warm starts in and out.
#include "cdyn/schemes/scheme_memory.hpp"

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

[[noreturn]] void missing(const std::string& name) {
  throw InputError("memory", "the scheme's memory has no entry '" + name + "' (it was written by another scheme)");
}

}  // namespace

const Eigen::VectorXd& SchemeMemory::vector(const std::string& name) const {
  const auto it = vectors.find(name);
  if (it == vectors.end()) missing(name);
  return it->second;
}

double SchemeMemory::number(const std::string& name) const {
  const auto it = numbers.find(name);
  if (it == numbers.end()) missing(name);
  return it->second;
}

void SchemeMemory::store_if_any(const std::string& name, const Eigen::VectorXd& v) {
  if (v.size()) vectors[name] = v;
}

Eigen::VectorXd SchemeMemory::vector_or_empty(const std::string& name) const {
  const auto it = vectors.find(name);
  return it == vectors.end() ? Eigen::VectorXd() : it->second;
}

void store_warm_start(SchemeMemory& m, const std::string& prefix, const QPResult& result, bool present) {
  if (!present) return;
  m.vectors[prefix + ".X"] = result.X;
  m.indices[prefix + ".active"] = result.active;
}

bool load_warm_start(const SchemeMemory& m, const std::string& prefix, QPResult& result) {
  const auto X = m.vectors.find(prefix + ".X");
  if (X == m.vectors.end()) return false;
  result = QPResult{};
  result.X = X->second;
  const auto active = m.indices.find(prefix + ".active");
  if (active != m.indices.end()) result.active = active->second;
  return true;
}

}  // namespace cdyn
