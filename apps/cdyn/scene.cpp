// scene.cpp — reading, validating and overriding scene files.
#include "scene.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "cdyn/base/error.hpp"
#include "default_scene.hpp"

namespace cdyn::app {

namespace {

// Every key a scene may contain.  Tables under "output.probes" hold user names; a "*"
// stands for a name the user chooses (a gmsh parameter, a region), whose keys are
// checked like the others (pattern_of).
const std::set<std::string> kKnownKeys = {
    "name",           "description",    "units",
    "mesh.kind",      "mesh.n",         "mesh.length",     "mesh.file",       "mesh.set.*",
    "materials.*.E",  "materials.*.nu", "materials.*.lambda", "materials.*.mu", "materials.*.rho",
    "physics.model",  "physics.E",      "physics.rho",     "physics.tension", "physics.f",
    "physics.m",      "physics.k",
    "physics.nu",     "physics.lambda", "physics.mu",      "physics.gravity",
    "dirichlet.parts", "dirichlet.value", "dirichlet.components",
    "neumann.parts",  "neumann.traction",
    "obstacle.enabled", "obstacle.where", "obstacle.g",
    "obstacle.point", "obstacle.normal", "obstacle.gap",
    "obstacles",      "obstacle.friction", "obstacle.mu",  "obstacle.threshold",
    "contact.friction", "contact.mu",   "contact.threshold",
    "initial.u",      "initial.v",
    "method.pair",    "method.mass",
    "time.scheme",    "time.dt",        "time.T",
    "time.beta",      "time.gamma",     "time.restitution", "time.reconstruct", "time.energy_tol",
    "damping.alpha",  "damping.beta",
    "solver.name",    "solver.tol",     "solver.max_iterations",
    "solver.condense", "solver.cg_iterations", "solver.free_block", "solver.linear", "solver.threads",
    "solver.backend", "solver.pc", "solver.partition",
    "exact.solution",
    "output.every",   "output.contact_every", "output.probes",  "output.fields",   "output.plots",
    "output.stress",  "output.wellposed",  "output.checkpoint_every",
};
const std::set<std::string> kFreeTables = {"output.probes"};
// The keys of each table of the array [[obstacles]] (elasticity: more rigid obstacles).
const std::set<std::string> kObstacleKeys = {"where", "point", "normal", "gap", "name", "friction", "mu", "threshold"};

// The key with its user-chosen name replaced by "*": mesh.set.h → mesh.set.*,
// materials.steel.E → materials.*.E (and the table materials.steel → materials.*).
std::string pattern_of(const std::string& key) {
  // the user's name is the component after "materials", or after "mesh.set"
  std::size_t begin = std::string::npos;
  if (key.rfind("materials.", 0) == 0) begin = 10;
  if (key.rfind("mesh.set.", 0) == 0) begin = 9;
  if (begin == std::string::npos) return key;
  const std::size_t end = key.find('.', begin);
  std::string out(key, 0, begin);
  out.push_back('*');
  if (end != std::string::npos) out.append(key, end, std::string::npos);
  return out;
}

bool is_known_key(const std::string& key) { return kKnownKeys.count(key) || kKnownKeys.count(pattern_of(key)); }

bool is_known_table(const std::string& key) {
  std::string prefix = pattern_of(key);
  prefix += '.';
  return std::any_of(kKnownKeys.begin(), kKnownKeys.end(),
                     [&](const std::string& k) { return k.rfind(prefix, 0) == 0; });
}

// The names of a table in the order they were written: toml++ keeps a table sorted
// by name, but each parsed node remembers where it was (line, column; an inline
// table's entries share a line).  Copies of a node lose that (toml++'s choice), so
// Scene keeps the order itself (order_).
std::vector<std::string> source_order(const toml::table& t) {
  std::vector<std::pair<toml::source_position, std::string>> named;
  for (const auto& [k, v] : t) named.emplace_back(v.source().begin, std::string(k.str()));
  std::stable_sort(named.begin(), named.end(), [](const auto& a, const auto& b) {
    return std::pair(a.first.line, a.first.column) < std::pair(b.first.line, b.first.column);
  });
  std::vector<std::string> out;
  for (auto& [at, name] : named) out.push_back(std::move(name));
  return out;
}

std::string type_name(const toml::node& n) {
  std::ostringstream s;
  s << n.type();
  return s.str();
}

}  // namespace

const char* default_scene_text() { return kDefaultSceneText; }

Scene Scene::from_string(const std::string& text, const std::string& source) {
  Scene s;
  s.source_ = source;
  try {
    s.table_ = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw InputError(source + ":" + std::to_string(b.line) + ":" + std::to_string(b.column) + ": " +
                     std::string(e.description()));
  }
  s.validate(s.table_, "");
  for (const std::string& key : kFreeTables)
    if (const toml::table* t = s.table_.at_path(key).as_table()) s.order_[key] = source_order(*t);
  s.name_ = s.string("name", std::filesystem::path(source).stem().string());
  return s;
}

Scene Scene::load(const std::string& path) {
  if (path.empty()) return from_string(default_scene_text(), "default");
  if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": no such scene file");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(path + ": cannot read the scene file");
  return from_string(text.str(), path);
}

Scene Scene::load(const std::string& path, const std::string& text) {
  return text.empty() ? load(path) : from_string(text, path);
}

void Scene::validate(const toml::table& t, const std::string& prefix) const {
  for (const auto& [k, node] : t) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (kFreeTables.count(key)) continue;
    if (key == "obstacles") {
      const toml::array* a = node.as_array();
      if (!a || !a->is_array_of_tables())
        throw InputError(source_ + ": obstacles: expected an array of tables ([[obstacles]])");
      for (std::size_t i = 0; i < a->size(); ++i)
        for (const auto& [sub, _] : *a->get(i)->as_table())
          if (!kObstacleKeys.count(std::string(sub.str())))
            throw InputError(source_ + ": unknown key 'obstacles[" + std::to_string(i) + "]." + std::string(sub.str()) +
                             "' (where, point, normal, gap, name, friction, mu, threshold)");
      continue;
    }
    if (node.is_table() && is_known_table(key)) {
      validate(*node.as_table(), key);
    } else if (!is_known_key(key)) {
      throw InputError(source_ + ": unknown key '" + key + "'");
    }
  }
}

void Scene::set(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError("--set " + assignment + ": expected key=value");
  const std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  // A known key, or a known table given whole (--set "mesh.set={ h = 0.05 }").
  const bool table = is_known_table(key) && !kFreeTables.count(key);
  if (!is_known_key(key) && !table) throw InputError("--set: unknown key '" + key + "'");
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    parsed.insert("v", value);  // a bare word: take it as a string
  }
  // Walk (and create) the tables of the dotted path, then replace the leaf.
  toml::table* t = &table_;
  std::size_t start = 0;
  for (std::size_t dot; (dot = key.find('.', start)) != std::string::npos; start = dot + 1) {
    const std::string part = key.substr(start, dot - start);
    auto [it, inserted] = t->insert(part, toml::table{});
    if (!it->second.is_table()) throw InputError("--set " + key + ": '" + part + "' is not a table");
    t = it->second.as_table();
  }
  if (table) {
    const toml::table* value = parsed.get("v")->as_table();
    if (!value) throw InputError("--set " + key + ": expected a table, e.g. { name = value }");
    validate(*value, key);
  }
  if (kFreeTables.count(key)) {
    const toml::table* names = parsed.get("v")->as_table();
    order_[key] = names ? source_order(*names) : std::vector<std::string>{};
  }
  t->insert_or_assign(key.substr(start), *parsed.get("v"));
  if (key == "name") name_ = string("name");  // (the value as TOML read it: --set name=\"x\" is x)
  // method.pair and method.mass are alternatives: overriding one replaces the other.
  if (key == "method.pair" || key == "method.mass") t->erase(key == "method.pair" ? "mass" : "pair");
  // Another mesh kind drops the keys the new kind does not take (else refused as
  // ignored, scene_spec.cpp): --set mesh.kind=gmsh on a unit_square scene works.
  if (key == "mesh.kind") {
    const auto* kind = t->get_as<std::string>("kind");
    const std::string k = kind ? kind->get() : "";
    if (k == "gmsh") t->erase("n");
    if (k != "interval") t->erase("length");
    if (k == "interval" || k == "unit_square" || k == "unit_cube") t->erase("file"), t->erase("set");
  }
}

const toml::node* Scene::find(const std::string& key) const {
  return table_.at_path(key).node();
}

bool Scene::has(const std::string& key) const { return find(key) != nullptr; }

std::size_t Scene::count(const std::string& key) const {
  const toml::node* n = find(key);
  const toml::array* a = n ? n->as_array() : nullptr;
  return a ? a->size() : 0;
}

const toml::node* Scene::find_required(const std::string& key, bool has_fallback) const {
  const toml::node* n = find(key);
  if (!n && !has_fallback) throw InputError(source_ + ": missing key '" + key + "'");
  return n;
}

double Scene::number(const std::string& key, std::optional<double> fallback) const {
  const toml::node* n = find_required(key, fallback.has_value());
  if (!n) return *fallback;
  if (auto v = n->value<double>()) return *v;  // integers convert too
  throw InputError(key + ": expected a number, got " + type_name(*n));
}

int Scene::integer(const std::string& key, std::optional<int> fallback) const {
  const toml::node* n = find_required(key, fallback.has_value());
  if (!n) return *fallback;
  if (auto v = n->value_exact<int64_t>()) {
    // TOML integers are 64-bit; every integer key of a scene is an int (mesh.n,
    // output.every, ...): a value beyond int would silently wrap (fuzz regression).
    if (*v < std::numeric_limits<int>::min() || *v > std::numeric_limits<int>::max())
      throw InputError(key + ": " + std::to_string(*v) + " is out of range");
    return static_cast<int>(*v);
  }
  throw InputError(key + ": expected an integer, got " + type_name(*n));
}

bool Scene::boolean(const std::string& key, std::optional<bool> fallback) const {
  const toml::node* n = find_required(key, fallback.has_value());
  if (!n) return *fallback;
  if (auto v = n->value_exact<bool>()) return *v;
  throw InputError(key + ": expected true or false, got " + type_name(*n));
}

std::string Scene::string(const std::string& key, std::optional<std::string> fallback) const {
  const toml::node* n = find_required(key, fallback.has_value());
  if (!n) return *fallback;
  if (auto v = n->value_exact<std::string>()) return *v;
  // Numbers given where an expression is expected ("f = -0.6" or --set physics.f=1)
  if (auto v = n->value<double>()) {
    std::ostringstream s;
    s.precision(17);
    s << *v;
    return s.str();
  }
  throw InputError(key + ": expected a string, got " + type_name(*n));
}

std::vector<std::string> Scene::strings(const std::string& key, std::vector<std::string> fallback) const {
  const toml::node* n = find(key);
  if (!n) return fallback;
  if (auto v = n->value_exact<std::string>()) return {*v};
  if (n->value<double>()) return {string(key)};  // one number where expressions are expected
  std::vector<std::string> out;
  if (const toml::array* a = n->as_array()) {
    for (const auto& e : *a) {
      if (auto v = e.value_exact<std::string>()) {
        out.push_back(*v);
      } else if (auto x = e.value<double>()) {  // a number where an expression is expected
        std::ostringstream text;
        text.precision(17);
        text << *x;
        out.push_back(text.str());
      } else {
        throw InputError(key + ": expected a list of strings");
      }
    }
    return out;
  }
  throw InputError(key + ": expected a string or a list of strings, got " + type_name(*n));
}

std::vector<double> Scene::numbers(const std::string& key) const {
  const toml::node* n = find(key);
  const toml::array* a = n ? n->as_array() : nullptr;
  if (!a) throw InputError(key + ": expected a list of numbers");
  std::vector<double> out;
  for (const auto& e : *a) {
    auto v = e.value<double>();
    if (!v) throw InputError(key + ": expected a list of numbers");
    out.push_back(*v);
  }
  return out;
}

std::vector<std::string> Scene::keys(const std::string& table) const {
  const toml::node* n = find(table);
  if (!n) return {};
  const toml::table* t = n->as_table();
  if (!t) throw InputError(table + ": expected a table");
  // The scene's order where it was recorded (output.probes), else toml++'s (by name).
  const auto it = order_.find(table);
  if (it != order_.end() && it->second.size() == t->size()) return it->second;
  std::vector<std::string> out;
  for (const auto& [k, v] : *t) out.emplace_back(k.str());
  return out;
}

std::string Scene::dump() const {
  // output.probes is written last, by hand, in the scene's order (keys()): toml++
  // would write it sorted by name, and a rerun of scene.toml would reorder the probes.
  toml::table copy = table_;
  const std::vector<std::string> probes = keys("output.probes");
  if (!probes.empty()) {
    toml::table* output = copy["output"].as_table();
    output->erase("probes");
    output->is_inline(false);  // an inline [output] could not take the [output.probes] below
  }
  std::ostringstream s;
  s << copy << "\n";
  if (probes.empty()) return s.str();
  s << "\n[output.probes]\n";
  const toml::table& table = *find("output.probes")->as_table();
  for (const std::string& name : probes) {
    toml::table one;  // one entry, so that toml++ quotes the name as TOML needs
    one.insert(name, *table.get(name));
    s << one << "\n";
  }
  return s.str();
}

}  // namespace cdyn::app
