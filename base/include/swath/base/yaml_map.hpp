#pragma once
// Internal: reading YAML mappings with errors that name the file, the line and the key path.

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "swath/base/yaml_input.hpp"

namespace swath::base {

/// A mapping at `path` ("battery", "power.mechanical", "" for the root) of `source`.
class YamlMap {
 public:
  YamlMap(const YAML::Node& node, std::string source, std::string path);

  /// Throws for a key not in `keys` (a typo would otherwise be silently ignored). A key spelled
  /// the old way, `..._mps` for an allowed `..._m_s`, is read as the new one with a warning (one
  /// spelling of speeds everywhere, docs/architecture.md); both spellings at once are refused.
  void allow(std::initializer_list<const char*> keys) const;
  /// Warnings collected while reading this mapping and the mappings below it, in reading order.
  const std::vector<std::string>& warnings() const { return *warnings_; }
  bool has(const char* key) const { return static_cast<bool>(node_[key]); }
  /// The number at `key` (or `fallback` when absent), which must lie in [lo, hi]; `open_lo`
  /// excludes lo.
  double number(const char* key, double fallback, double lo, double hi, bool open_lo = false) const;
  bool flag(const char* key, bool fallback) const;
  std::string text(const char* key, const std::string& fallback) const;
  std::vector<double> numbers(const char* key) const;  ///< a list of numbers (absent: empty)
  YamlMap map(const char* key) const;                  ///< absent: an empty mapping
  /// "source: line N: path.key" for messages about a key.
  std::string where(const char* key) const;
  const YAML::Node& node() const { return node_; }

 private:
  YamlMap(const YAML::Node& node, std::string source, std::string path,
          std::shared_ptr<std::vector<std::string>> warnings);
  void accept_old_spelling(std::initializer_list<const char*> keys) const;

  YAML::Node node_;
  std::string source_, path_;
  std::shared_ptr<std::vector<std::string>> warnings_;
};

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace swath::base
