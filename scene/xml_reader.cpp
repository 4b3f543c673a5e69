// Strict XML reader (contract in xml_reader.h). A recursive-descent parser over the
// whole text; `m_line` counts newlines consumed so far.
#include "scene/xml_reader.h"

#include <fstream>
#include <sstream>

#include "core/error.h"

namespace dp::scene {

const std::string* XmlElement::attribute(const std::string& name) const {
  for (const auto& [k, v] : attributes)
    if (k == name) return &v;
  return nullptr;
}

const std::string& XmlElement::file_name() const {
  static const std::string kNone;
  return file ? *file : kNone;
}

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_name_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' || (unsigned char)c >= 0x80;
}
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

void append_utf8(std::string& out, unsigned long cp) {
  if (cp < 0x80) {
    out += char(cp);
  } else if (cp < 0x800) {
    out += char(0xC0 | (cp >> 6));
    out += char(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += char(0xE0 | (cp >> 12));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  } else {
    out += char(0xF0 | (cp >> 18));
    out += char(0x80 | ((cp >> 12) & 0x3F));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  }
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& file)
      : m_text(text), m_file(std::make_shared<const std::string>(file)) {}

  XmlElement parse_document() {
    if (m_text.compare(0, 3, "\xEF\xBB\xBF") == 0) m_pos = 3;  // UTF-8 byte order mark
    skip_misc();
    if (at_end() || peek() != '<') fail("expected the root element");
    XmlElement root = parse_element();
    skip_misc();
    if (!at_end()) fail("unexpected content after the root element </" + root.tag + ">");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& msg) const { throw ParseError("malformed XML: " + msg, *m_file, m_line); }
  bool at_end() const { return m_pos >= m_text.size(); }
  char peek() const { return m_text[m_pos]; }
  bool starts_with(const char* s) const { return m_text.compare(m_pos, std::char_traits<char>::length(s), s) == 0; }
  void advance(size_t n = 1) {
    for (size_t i = 0; i < n && m_pos < m_text.size(); ++i)
      if (m_text[m_pos++] == '\n') ++m_line;
  }
  void skip_space() {
    while (!at_end() && is_space(peek())) advance();
  }
  // Skips everything up to and including `end`; fails with `what` if it never comes.
  void skip_past(const char* end, const std::string& what) {
    const size_t at = m_text.find(end, m_pos);
    if (at == std::string::npos) fail("unterminated " + what);
    advance(at + std::char_traits<char>::length(end) - m_pos);
  }
  // Whitespace, comments and processing instructions outside the root element.
  void skip_misc() {
    for (;;) {
      skip_space();
      if (starts_with("<!--")) {
        skip_comment();
      } else if (starts_with("<?")) {
        skip_past("?>", "processing instruction");
      } else if (starts_with("<!DOCTYPE")) {
        fail("DOCTYPE declarations are not supported");
      } else {
        return;
      }
    }
  }
  void skip_comment() {
    advance(4);
    const size_t at = m_text.find("--", m_pos);
    if (at == std::string::npos) fail("unterminated comment");
    advance(at - m_pos);
    if (!starts_with("-->")) fail("'--' inside a comment");
    advance(3);
  }
  std::string parse_name(const char* what) {
    if (at_end() || !is_name_start(peek())) fail(std::string("expected ") + what);
    const size_t start = m_pos;
    while (!at_end() && is_name_char(peek())) advance();
    return m_text.substr(start, m_pos - start);
  }
  void decode_entity(std::string& out) {
    const size_t semi = m_text.find(';', m_pos);
    if (semi == std::string::npos || semi - m_pos > 12) fail("unterminated entity reference");
    const std::string ent = m_text.substr(m_pos + 1, semi - m_pos - 1);
    if (ent == "lt") out += '<';
    else if (ent == "gt") out += '>';
    else if (ent == "amp") out += '&';
    else if (ent == "quot") out += '"';
    else if (ent == "apos") out += '\'';
    else if (ent.size() > 1 && ent[0] == '#') {
      const bool hex = ent[1] == 'x' || ent[1] == 'X';
      const std::string digits = ent.substr(hex ? 2 : 1);
      if (digits.empty() || digits.find_first_not_of(hex ? "0123456789abcdefABCDEF" : "0123456789") != std::string::npos)
        fail("invalid character reference '&" + ent + ";'");
      const unsigned long cp = std::stoul(digits, nullptr, hex ? 16 : 10);
      if (cp == 0 || cp > 0x10FFFF) fail("character reference '&" + ent + ";' out of range");
      append_utf8(out, cp);
    } else {
      fail("unknown entity '&" + ent + ";'");
    }
    advance(semi + 1 - m_pos);
  }
  std::string parse_attribute_value() {
    if (at_end() || (peek() != '"' && peek() != '\'')) fail("attribute value must be quoted");
    const char quote = peek();
    advance();
    std::string out;
    for (;;) {
      if (at_end()) fail("unterminated attribute value");
      const char c = peek();
      if (c == quote) break;
      if (c == '<') fail("'<' inside an attribute value (write &lt;)");
      if (c == '&') {
        decode_entity(out);
      } else {
        out += c;
        advance();
      }
    }
    advance();
    return out;
  }
  XmlElement parse_element() {
    XmlElement e;
    e.file = m_file;
    e.line = m_line;
    advance();  // '<'
    e.tag = parse_name("an element name");
    for (;;) {
      const bool had_space = !at_end() && is_space(peek());
      skip_space();
      if (at_end()) fail("unterminated tag <" + e.tag + ">");
      if (starts_with("/>")) {
        advance(2);
        return e;
      }
      if (peek() == '>') {
        advance();
        break;
      }
      if (!had_space) fail("expected whitespace between attributes of <" + e.tag + ">");
      const std::string name = parse_name("an attribute name");
      skip_space();
      if (at_end() || peek() != '=') fail("expected '=' after attribute '" + name + "'");
      advance();
      skip_space();
      std::string value = parse_attribute_value();
      if (e.attribute(name)) fail("duplicate attribute '" + name + "' in <" + e.tag + ">");
      e.attributes.emplace_back(name, std::move(value));
    }
    parse_content(e);
    return e;
  }
  void parse_content(XmlElement& e) {
    for (;;) {
      if (at_end()) fail("element <" + e.tag + "> (line " + std::to_string(e.line) + ") is never closed");
      const char c = peek();
      if (is_space(c)) {
        advance();
      } else if (starts_with("<!--")) {
        skip_comment();
      } else if (starts_with("<![CDATA[")) {
        fail("CDATA sections are not supported");
      } else if (starts_with("<?")) {
        skip_past("?>", "processing instruction");
      } else if (starts_with("</")) {
        advance(2);
        const std::string name = parse_name("a closing tag name");
        skip_space();
        if (at_end() || peek() != '>') fail("expected '>' in closing tag </" + name + ">");
        if (name != e.tag)
          fail("closing tag </" + name + "> does not match <" + e.tag + "> (line " + std::to_string(e.line) + ")");
        advance();
        return;
      } else if (c == '<') {
        e.children.push_back(parse_element());
      } else {
        fail("unexpected text inside <" + e.tag + "> (scene files carry values in attributes)");
      }
    }
  }

  const std::string& m_text;
  std::shared_ptr<const std::string> m_file;
  size_t m_pos = 0;
  int m_line = 1;
};

}  // namespace

XmlElement parse_xml(const std::string& text, const std::string& file) { return Parser(text, file).parse_document(); }

XmlElement parse_xml_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open XML file", path);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IoError("cannot read XML file", path);
  return parse_xml(ss.str(), path);
}

}  // namespace dp::scene
