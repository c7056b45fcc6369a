// scene.hpp — a scene file (TOML, docs/scenes.md) with its --set overrides.
//
// A scene is a TOML table whose every key must be known (a typo is an error, never
// silently ignored).  --set key=value overrides any key by its dotted name; the value
// is read as a TOML value (number, boolean, array, quoted string) and, failing that,
// as a bare string (so --set time.scheme=backward_euler works).  Accessors name the
// key in every error.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <toml++/toml.h>
#include <vector>

namespace cdyn::app {

class Scene {
 public:
  // Reads a scene file; an empty path gives the embedded default scene (the seed's
  // membrane experiment).
  static Scene load(const std::string& path);
  // The scene of a command: the file `path` or, when `text` is not empty, the TOML text
  // `text` with `path` naming its source (a scene built by a program: a Python dict).
  static Scene load(const std::string& path, const std::string& text);
  static Scene from_string(const std::string& text, const std::string& source);

  // Applies one "key=value" override.
  void set(const std::string& assignment);

  const std::string& name() const { return name_; }
  const std::string& source() const { return source_; }
  bool has(const std::string& key) const;
  // The length of an array (0 when absent); its elements are "key[i]" (toml++ paths:
  // obstacles[1].where).
  std::size_t count(const std::string& key) const;

  double number(const std::string& key, std::optional<double> fallback = {}) const;
  int integer(const std::string& key, std::optional<int> fallback = {}) const;
  bool boolean(const std::string& key, std::optional<bool> fallback = {}) const;
  std::string string(const std::string& key, std::optional<std::string> fallback = {}) const;
  // A string or a list of strings (numbers, alone or in the list, are read as their text, so
  // that a list of expressions may hold plain numbers: traction = [0, -10]).
  std::vector<std::string> strings(const std::string& key, std::vector<std::string> fallback = {}) const;
  std::vector<double> numbers(const std::string& key) const;
  // The names under a table key (e.g. the probes of output.probes); for
  // output.probes in the order the scene (or the --set) wrote them.
  std::vector<std::string> keys(const std::string& table) const;

  // The scene as TOML text (with overrides applied), written next to the results.
  std::string dump() const;

 private:
  const toml::node* find(const std::string& key) const;
  // The node of a key; nullptr when absent and a fallback exists, else InputError.
  const toml::node* find_required(const std::string& key, bool has_fallback) const;
  void validate(const toml::table& t, const std::string& prefix) const;

  toml::table table_;
  std::string name_, source_;
  std::map<std::string, std::vector<std::string>> order_;  // output.probes: the names as written
};

// The embedded default scene's text.
const char* default_scene_text();

}  // namespace cdyn::app
