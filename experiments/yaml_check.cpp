#include "experiments/yaml_check.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>

#include "core/error.h"
#include "core/number_syntax.h"

namespace dp::experiments::yamlx {

namespace {
const char* type_name(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return "a scalar";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    default: return "an undefined value";
  }
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& a : v) s += (s.empty() ? "" : ", ") + a;
  return s;
}

// Quoted scalars ("5") are text, never numbers.
bool is_plain_scalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() != "!"; }
}  // namespace

int line_of(const YAML::Node& node) {
  if (!node.IsDefined()) return 0;
  const YAML::Mark m = node.Mark();
  return m.line >= 0 ? m.line + 1 : 0;
}

void parse_error(const Ctx& ctx, const YAML::Node& at, const std::string& message) {
  throw ParseError(message, ctx.file, line_of(at));
}

void value_error(const Ctx& ctx, const YAML::Node& at, const std::string& message) {
  throw ValueError(message, ctx.file, line_of(at));
}

void check_keys(const Ctx& ctx, const YAML::Node& node, const std::vector<std::string>& allowed,
                const std::string& what) {
  if (!node.IsMap()) parse_error(ctx, node, what + ": expected a map, got " + type_name(node));
  std::set<std::string> seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (!it->first.IsScalar()) parse_error(ctx, it->first, what + ": keys must be plain names");
    const std::string key = it->first.Scalar();
    bool known = false;
    for (const auto& a : allowed) known |= (a == key);
    if (!known) parse_error(ctx, it->first, "unknown key '" + key + "' in " + what + " (allowed: " + join(allowed) + ")");
    if (!seen.insert(key).second) parse_error(ctx, it->first, "duplicate key '" + key + "' in " + what);
  }
}

YAML::Node require(const Ctx& ctx, const YAML::Node& map, const std::string& key, const std::string& what) {
  const YAML::Node v = map[key];
  if (!v.IsDefined() || v.IsNull()) parse_error(ctx, map, "missing required key '" + key + "' in " + what);
  return v;
}

std::string get_string(const Ctx& ctx, const YAML::Node& node, const std::string& name) {
  if (!node.IsScalar() || node.Scalar().empty())
    parse_error(ctx, node, "'" + name + "': expected a name or text, got " + type_name(node));
  return node.Scalar();
}

double get_number(const Ctx& ctx, const YAML::Node& node, const std::string& name) {
  if (!is_plain_scalar(node)) parse_error(ctx, node, "'" + name + "': expected a number, got " + type_name(node));
  const std::string& s = node.Scalar();
  std::string lower;
  for (char c : s) lower += char(std::tolower(static_cast<unsigned char>(c)));
  if (lower.find("inf") != std::string::npos || lower.find("nan") != std::string::npos)
    value_error(ctx, node, "'" + name + "': not a finite number (" + quote_input(s) + ")");
  if (!core::is_decimal_number(s))  // std::strtod alone would also read hex ("0x10")
    parse_error(ctx, node, "'" + name + "': expected a number, got '" + quote_input(s) + "'");
  errno = 0;
  const double v = std::strtod(s.c_str(), nullptr);
  if (errno == ERANGE || !std::isfinite(v)) value_error(ctx, node, "'" + name + "': not a finite number (" + quote_input(s) + ")");
  return v;
}

long long get_integer(const Ctx& ctx, const YAML::Node& node, const std::string& name) {
  if (!is_plain_scalar(node)) parse_error(ctx, node, "'" + name + "': expected an integer, got " + type_name(node));
  const std::string& s = node.Scalar();
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size())
    parse_error(ctx, node, "'" + name + "': expected an integer, got '" + quote_input(s) + "'");
  if (errno == ERANGE) value_error(ctx, node, "'" + name + "': integer out of range (" + quote_input(s) + ")");
  return v;
}

std::vector<YAML::Node> get_list(const Ctx& ctx, const YAML::Node& node, const std::string& name, bool allow_scalar) {
  std::vector<YAML::Node> out;
  if (allow_scalar && node.IsScalar()) {
    out.push_back(node);
    return out;
  }
  if (!node.IsSequence()) parse_error(ctx, node, "'" + name + "': expected a list, got " + type_name(node));
  for (const auto& n : node) out.push_back(n);
  return out;
}

std::string resolve_path(const Ctx& ctx, const std::string& relative) {
  const std::filesystem::path p(relative);
  if (p.is_absolute() || ctx.base_dir.empty()) return p.lexically_normal().string();
  return (ctx.base_dir / p).lexically_normal().string();
}

}  // namespace dp::experiments::yamlx
