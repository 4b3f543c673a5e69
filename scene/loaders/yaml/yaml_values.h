// Typed access to yaml-cpp nodes for the YAML scene loader and for experiment files (the
// one YAML value helper of scene/ and experiments/). Every failure throws a dp::Error
// subclass whose what() is "file:line: problem", the line taken from the node's
// YAML::Mark (1-based): ParseError for structure (missing/unknown keys, wrong types,
// undefined names), ValueError for values (non-finite numbers, out-of-range values).
// Not part of the scene API.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/math.h"

namespace dp::scene::yaml {

struct Context {
  std::string file;                // the scene or experiment file, as given (used in messages)
  std::filesystem::path base_dir;  // relative paths in the scene resolve against this
};

// 1-based line of the node, or 0 if yaml-cpp has no position for it.
int line_of(const YAML::Node& node);

[[noreturn]] void parse_error(const Context& ctx, const YAML::Node& at, const std::string& message);
[[noreturn]] void value_error(const Context& ctx, const YAML::Node& at, const std::string& message);

// Structure checks. `what` names the thing in messages, e.g. "sphere shape".
void expect_map(const Context& ctx, const YAML::Node& node, const std::string& what);
void expect_sequence(const Context& ctx, const YAML::Node& node, const std::string& what);
// Throws ParseError on the first key of `map` not in `allowed` (at that key's line),
// and on duplicated keys.
void check_keys(const Context& ctx, const YAML::Node& map, const std::vector<std::string_view>& allowed,
                const std::string& what);
// The value of a required key; ParseError at the map's line if absent.
YAML::Node require(const Context& ctx, const YAML::Node& map, const std::string& key, const std::string& what);

// Scalars. `name` is the key (or a description) used in messages.
// A finite decimal number (ValueError for .inf/.nan or overflow, ParseError for "0x10").
double get_number(const Context& ctx, const YAML::Node& node, const std::string& name);
// get_number within the scene limit (scene/limits.h), as float.
float get_float(const Context& ctx, const YAML::Node& node, const std::string& name);
// A decimal integer (ParseError for "3.5"; ValueError beyond long long).
long long get_integer(const Context& ctx, const YAML::Node& node, const std::string& name);
// get_integer within +-1e9.
int get_int(const Context& ctx, const YAML::Node& node, const std::string& name);
bool get_bool(const Context& ctx, const YAML::Node& node, const std::string& name);
std::string get_string(const Context& ctx, const YAML::Node& node, const std::string& name);

// A list; a single scalar is accepted as a list of one when `allow_scalar`.
std::vector<YAML::Node> get_list(const Context& ctx, const YAML::Node& node, const std::string& name,
                                 bool allow_scalar = false);

// Fixed-size lists of finite numbers.
Vec2 get_vec2(const Context& ctx, const YAML::Node& node, const std::string& name);
Vec3 get_vec3(const Context& ctx, const YAML::Node& node, const std::string& name);
// RGB: a list [r, g, b] or a single number (grey). Components must be >= 0.
Rgb get_rgb(const Context& ctx, const YAML::Node& node, const std::string& name);
// Unit direction from a list of 3 numbers; ValueError for the zero vector.
Vec3 get_direction(const Context& ctx, const YAML::Node& node, const std::string& name);

// Optional-key helpers: the default when the key is absent.
float get_float_or(const Context& ctx, const YAML::Node& map, const std::string& key, float fallback);
std::string get_string_or(const Context& ctx, const YAML::Node& map, const std::string& key,
                          const std::string& fallback);

// Range checks (ValueError at the node's line).
void check_positive(const Context& ctx, const YAML::Node& node, const std::string& name, float v);
void check_nonnegative(const Context& ctx, const YAML::Node& node, const std::string& name, float v);

// A path from the scene file, resolved against Context::base_dir unless absolute.
std::string resolve_path(const Context& ctx, const std::string& relative);

// Flow-style text of any node (scalars as written), e.g. for verbatim settings.
std::string to_text(const YAML::Node& node);

}  // namespace dp::scene::yaml
