// Minimal JSON writer for sidecars, CSV-adjacent reports and experiment state.
// Builds a value tree and prints it; non-finite numbers are written as null.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <limits>
#include <variant>
#include <vector>

namespace dp::core {

class Json {
 public:
  using Object = std::vector<std::pair<std::string, Json>>;  // keeps insertion order
  using Array = std::vector<Json>;

  Json() : m_value(nullptr) {}
  Json(std::nullptr_t) : m_value(nullptr) {}
  Json(bool b) : m_value(b) {}
  Json(int v) : m_value(double(v)) {}
  Json(int64_t v) : m_value(double(v)) {}
  Json(uint64_t v) : m_value(double(v)) {}
  Json(double v) : m_value(v) {}
  Json(float v) : m_value(double(v)) {}
  Json(const char* s) : m_value(std::string(s)) {}
  Json(std::string s) : m_value(std::move(s)) {}
  Json(Array a) : m_value(std::move(a)) {}
  static Json object() { Json j; j.m_value = Object{}; return j; }
  static Json array() { Json j; j.m_value = Array{}; return j; }

  // Object access: inserts the key if missing.
  Json& operator[](const std::string& key);
  void push_back(Json v);
  // The number held (NaN if this is not a number).
  double number() const {
    const double* d = std::get_if<double>(&m_value);
    return d ? *d : std::numeric_limits<double>::quiet_NaN();
  }
  std::string dump(int indent = 2) const;

 private:
  void dump_to(std::string& out, int indent, int depth) const;
  std::variant<std::nullptr_t, bool, double, std::string, Array, Object> m_value;
};

std::string json_escape(const std::string& s);

}  // namespace dp::core
