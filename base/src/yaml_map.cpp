#include "swath/base/yaml_map.hpp"

#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"

namespace swath::base {

YamlMap::YamlMap(const YAML::Node& node, std::string source, std::string path)
    : YamlMap(node, std::move(source), std::move(path),
              std::make_shared<std::vector<std::string>>()) {}

YamlMap::YamlMap(const YAML::Node& node, std::string source, std::string path,
                 std::shared_ptr<std::vector<std::string>> warnings)
    : node_(node),
      source_(std::move(source)),
      path_(std::move(path)),
      warnings_(std::move(warnings)) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) {
    std::string msg = source_ + ": line " + std::to_string(node_.Mark().line + 1) + ": ";
    msg += path_.empty() ? std::string("the file") : "'" + path_ + "'";
    msg += " must be a mapping of keys";
    throw InputError(msg);
  }
}

std::string YamlMap::where(const char* key) const {
  const YAML::Node n = node_ && node_.IsMap() && node_[key] ? node_[key] : node_;
  std::string s = source_;
  if (n && n.Mark().line >= 0) s += ": line " + std::to_string(n.Mark().line + 1);
  s += ": ";
  s += path_.empty() ? std::string(key) : path_ + "." + key;
  return s;
}

void YamlMap::accept_old_spelling(std::initializer_list<const char*> keys) const {
  static const std::string kOld = "_mps", kNew = "_m_s";
  std::vector<std::pair<std::string, std::string>> renames;
  for (const auto& kv : node_) {
    const std::string k = kv.first.Scalar();
    if (k.size() <= kOld.size() || k.compare(k.size() - kOld.size(), kOld.size(), kOld) != 0)
      continue;
    const std::string renamed = k.substr(0, k.size() - kOld.size()) + kNew;
    for (const char* allowed : keys)
      if (renamed == allowed) renames.emplace_back(k, renamed);
  }
  YAML::Node node = node_;  // shares the document: the rename is seen by every later read
  for (const auto& [old_key, key] : renames) {
    const std::string line = std::to_string(node[old_key].Mark().line + 1);
    const std::string shown = path_.empty() ? old_key : path_ + "." + old_key;
    if (node[key])
      throw InputError(source_ + ": line " + line + ": '" + shown + "' and '" + key +
                       "' both given: keep '" + key + "'");
    node[key] = node[old_key];
    node.remove(old_key);
    warnings_->push_back(source_ + ": line " + line + ": '" + shown +
                         "' is the old spelling, read as '" + key + "'; write '" + key +
                         "' (speeds are in m_s everywhere)");
  }
}

void YamlMap::allow(std::initializer_list<const char*> keys) const {
  if (!node_ || !node_.IsMap()) return;
  base::check_plain_unique_keys(node_, path_.empty() ? source_ : source_ + ": " + path_);
  accept_old_spelling(keys);
  for (const auto& kv : node_) {
    const std::string k = kv.first.Scalar();
    bool ok = false;
    for (const char* allowed : keys) ok = ok || k == allowed;
    if (!ok) {
      std::string msg = source_ + ": line " + std::to_string(kv.first.Mark().line + 1) +
                        ": unknown key '" + (path_.empty() ? k : path_ + "." + k) + "' (known:";
      for (const char* allowed : keys) {
        msg += ' ';
        msg += allowed;
      }
      msg += ")";
      throw InputError(msg);
    }
  }
}

double YamlMap::number(const char* key, double fallback, double lo, double hi, bool open_lo) const {
  if (!node_ || !node_.IsMap() || !node_[key]) return fallback;
  double v = 0.0;
  try {
    v = node_[key].as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(where(key) + " must be a number");
  }
  if (!std::isfinite(v) || v < lo || v > hi || (open_lo && v == lo)) {
    std::string msg = where(key) + " must be ";
    if (hi == kInf) {
      msg += open_lo ? "> " : ">= ";
      msg += base::fixed_text(lo, 4);
    } else {
      msg += "in ";
      msg += open_lo ? "(" : "[";
      msg += base::fixed_text(lo, 4) + ", " + base::fixed_text(hi, 4) + "]";
    }
    msg += ", found " + node_[key].as<std::string>();
    throw InputError(msg);
  }
  return v;
}

bool YamlMap::flag(const char* key, bool fallback) const {
  if (!node_ || !node_.IsMap() || !node_[key]) return fallback;
  try {
    return node_[key].as<bool>();
  } catch (const YAML::Exception&) {
    throw InputError(where(key) + " must be true or false");
  }
}

std::string YamlMap::text(const char* key, const std::string& fallback) const {
  if (!node_ || !node_.IsMap() || !node_[key]) return fallback;
  if (!node_[key].IsScalar()) throw InputError(where(key) + " must be a text");
  return node_[key].as<std::string>();
}

std::vector<double> YamlMap::numbers(const char* key) const {
  std::vector<double> out;
  if (!node_ || !node_.IsMap() || !node_[key]) return out;
  const YAML::Node n = node_[key];
  if (!n.IsSequence()) throw InputError(where(key) + " must be a list of numbers");
  for (const YAML::Node& v : n) {
    try {
      out.push_back(v.as<double>());
    } catch (const YAML::Exception&) {
      throw InputError(where(key) + " must be a list of numbers");
    }
    if (!std::isfinite(out.back())) throw InputError(where(key) + " must hold finite numbers");
  }
  return out;
}

YamlMap YamlMap::map(const char* key) const {
  const YAML::Node n = node_ && node_.IsMap() && node_[key] ? node_[key] : YAML::Node();
  return YamlMap(n, source_, path_.empty() ? key : path_ + "." + key, warnings_);
}

}  // namespace swath::base
