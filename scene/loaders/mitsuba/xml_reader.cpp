// Strict XML reader (contract in xml_reader.h) on top of pugixml. pugixml does the
// tokenising and builds its tree without recursion; this file adds what pugixml accepts
// but scene files must not contain (see the header), decodes entities itself (pugixml
// keeps unknown ones verbatim) and copies the tree into XmlElements, refusing it deeper
// than kMaxDepth so that no recursive walk (the copy, ~XmlElement, the importer) can
// exhaust the stack.
#include "scene/loaders/mitsuba/xml_reader.h"

#include <pugixml.hpp>

#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/read_file.h"

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

constexpr int kMaxDepth = 256;  // the root element is depth 1
constexpr size_t kMaxQuote = 60;

// `s` for a one-line message: at most kMaxQuote characters, control characters as '?'.
std::string quote(std::string_view s) {
  std::string out(s.substr(0, kMaxQuote));
  for (char& c : out)
    if ((unsigned char)c < 0x20) c = '?';
  return s.size() > kMaxQuote ? out + "..." : out;
}

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

// The five predefined entities and character references; anything else is an error.
// Returns false with `error` set and `i` at the offending character.
bool decode_entities(std::string_view raw, std::string& out, std::string& error, size_t& i) {
  for (i = 0; i < raw.size(); ++i) {
    if (raw[i] == '<') return error = "'<' inside an attribute value (write &lt;)", false;
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    const size_t semi = raw.find(';', i);
    if (semi == std::string_view::npos || semi - i > 12) return error = "unterminated entity reference", false;
    const std::string ent(raw.substr(i + 1, semi - i - 1));
    if (ent == "lt") out += '<';
    else if (ent == "gt") out += '>';
    else if (ent == "amp") out += '&';
    else if (ent == "quot") out += '"';
    else if (ent == "apos") out += '\'';
    else if (ent.size() > 1 && ent[0] == '#') {
      const bool hex = ent[1] == 'x' || ent[1] == 'X';
      const std::string digits = ent.substr(hex ? 2 : 1);
      if (digits.empty() || digits.find_first_not_of(hex ? "0123456789abcdefABCDEF" : "0123456789") != std::string::npos)
        return error = "invalid character reference '&" + ent + ";'", false;
      const unsigned long cp = std::stoul(digits, nullptr, hex ? 16 : 10);
      if (cp == 0 || cp > 0x10FFFF) return error = "character reference '&" + ent + ";' out of range", false;
      append_utf8(out, cp);
    } else {
      return error = "unknown entity '&" + ent + ";'", false;
    }
    i = semi;
  }
  return true;
}

class Reader {
 public:
  Reader(const std::string& text, const std::string& file)
      : m_text(text), m_file(std::make_shared<const std::string>(file)) {
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') m_newlines.push_back(i);
  }

  XmlElement read() {
    if (const size_t nul = m_text.find('\0'); nul != std::string::npos) fail(nul, "NUL byte in the input");
    // In place, so that every name and value pugixml returns points into m_buf and its
    // offset gives the line. The extra newline: with parse_fragment in place, pugixml
    // drops the buffer's last character, and text after the root must still be seen.
    m_buf.assign(m_text.begin(), m_text.end());
    m_buf.push_back('\n');
    pugi::xml_document doc;
    // No parse_escapes/eol/wconv: values arrive verbatim. parse_fragment keeps text
    // outside the root as nodes; DOCTYPE and CDATA become nodes so they can be refused.
    const unsigned options = pugi::parse_comments | pugi::parse_cdata | pugi::parse_doctype | pugi::parse_fragment;
    const pugi::xml_parse_result r = doc.load_buffer_inplace(m_buf.data(), m_buf.size(), options, pugi::encoding_utf8);
    if (!r) fail_parse(r);

    pugi::xml_node root;
    for (pugi::xml_node n : doc.children()) {
      check_misc(n);
      const bool content = n.type() == pugi::node_element || n.type() == pugi::node_pcdata;
      if (content && root) fail(n, "unexpected content after the root element </" + quote(root.name()) + ">");
      if (n.type() == pugi::node_pcdata) fail(n, "expected the root element");
      if (n.type() == pugi::node_element) root = n;
    }
    if (!root) fail(m_text.size(), "expected the root element");
    return convert(root, 1);
  }

 private:
  int line_of(size_t offset) const {
    return 1 + int(std::lower_bound(m_newlines.begin(), m_newlines.end(), offset) - m_newlines.begin());
  }
  size_t offset_of(const char* p) const { return size_t(p - m_buf.data()); }
  [[noreturn]] void fail(size_t offset, const std::string& msg) const {
    throw ParseError("malformed XML: " + msg, *m_file, line_of(offset));
  }
  // At the first non-blank character of a text node, or the '<' of any other node
  // (pugixml's offset is that of the name, or of the value: "<!DOCTYPE ", "<![CDATA[").
  [[noreturn]] void fail(pugi::xml_node n, const std::string& msg) const {
    size_t at = size_t(n.offset_debug());
    if (n.type() == pugi::node_pcdata)
      at += std::string_view(n.value()).find_first_not_of(" \t\r\n");
    else
      at = m_text.rfind('<', at);
    fail(at, msg);
  }

  // Comments are skipped (but '--' inside one is an error, as XML says); DOCTYPE, CDATA
  // and non-blank text are refused. pugixml drops blank text itself.
  void check_misc(pugi::xml_node n) const {
    switch (n.type()) {
      case pugi::node_comment: {
        const std::string_view v = n.value();
        if (v.find("--") != std::string_view::npos || (!v.empty() && v.back() == '-')) fail(n, "'--' inside a comment");
        break;
      }
      case pugi::node_doctype: fail(n, "DOCTYPE declarations are not supported");
      case pugi::node_cdata: fail(n, "CDATA sections are not supported");
      default: break;
    }
  }

  XmlElement convert(pugi::xml_node n, int depth) const {
    XmlElement e;
    e.file = m_file;
    e.line = line_of(size_t(n.offset_debug()) - 1);  // the '<' before the name
    if (depth > kMaxDepth) throw ParseError("elements nested deeper than " + std::to_string(kMaxDepth), *m_file, e.line);
    e.tag = n.name();
    for (pugi::xml_attribute a : n.attributes()) {
      if (e.attribute(a.name()))
        fail(offset_of(a.name()), "duplicate attribute '" + quote(a.name()) + "' in <" + quote(e.tag) + ">");
      std::string value, error;
      size_t i = 0;
      // An empty value may not point into the buffer; it needs no decoding anyway.
      if (*a.value() && !decode_entities(a.value(), value, error, i)) fail(offset_of(a.value()) + i, error);
      e.attributes.emplace_back(a.name(), std::move(value));
    }
    for (pugi::xml_node c : n.children()) {
      check_misc(c);
      if (c.type() == pugi::node_pcdata)
        fail(c, "unexpected text inside <" + quote(e.tag) + "> (scene files carry values in attributes)");
      if (c.type() == pugi::node_element) e.children.push_back(convert(c, depth + 1));
    }
    return e;
  }

  [[noreturn]] void fail_parse(const pugi::xml_parse_result& r) const {
    const size_t at = std::min(size_t(r.offset), m_text.size());
    std::string what;
    switch (r.status) {
      case pugi::status_end_element_mismatch: fail_mismatch(at);
      case pugi::status_bad_comment:  // pugixml points at the end: report the comment's start
        fail(std::min(at, m_text.rfind("<!--", at)), "unterminated comment");
      case pugi::status_bad_cdata: fail(at, "CDATA sections are not supported");
      case pugi::status_bad_doctype: fail(at, "DOCTYPE declarations are not supported");
      case pugi::status_bad_attribute:
        fail(at, "malformed attribute (values must be quoted, attributes separated by whitespace)");
      case pugi::status_bad_pi: what = "invalid processing instruction"; break;
      case pugi::status_bad_start_element: what = "invalid start tag"; break;
      case pugi::status_bad_end_element: what = "invalid closing tag"; break;
      case pugi::status_unrecognized_tag: what = "unrecognized tag"; break;
      default: what = r.description(); break;
    }
    if (at == m_text.size()) fail(at, what + " at the end of the input");
    fail(at, what + " near '" + quote(std::string_view(m_text).substr(at)) + "'");
  }

  // pugixml reports a closing tag that does not match (offset at its name) or the end of
  // the input with elements open (offset at the end), but not which element is open. To
  // name it, parse the text up to that point followed by a probe element: the probe
  // becomes the last child of the innermost open element.
  [[noreturn]] void fail_mismatch(size_t at) const {
    const bool closing_tag = at >= 2 && m_text.compare(at - 2, 2, "</") == 0;
    std::string probe_text = m_text.substr(0, closing_tag ? at - 2 : m_text.size()) + "<probe/>\n";
    pugi::xml_document doc;
    doc.load_buffer_inplace(probe_text.data(), probe_text.size(), pugi::parse_fragment, pugi::encoding_utf8);
    pugi::xml_node probe = doc;
    while (probe.last_child()) probe = probe.last_child();
    const pugi::xml_node open = probe.parent();
    const std::string open_desc =
        "<" + quote(open.name()) + "> (line " + std::to_string(line_of(size_t(open.offset_debug()))) + ")";
    if (!closing_tag) fail(m_text.size(), "element " + open_desc + " is never closed");
    std::string_view name = std::string_view(m_text).substr(at);
    name = name.substr(0, name.find_first_of(" \t\r\n>"));
    if (open == doc) fail(at, "unexpected content after the root element");
    fail(at, "closing tag </" + quote(name) + "> does not match " + open_desc);
  }

  const std::string& m_text;
  std::shared_ptr<const std::string> m_file;
  std::vector<size_t> m_newlines;  // offsets of every '\n', ascending
  std::vector<char> m_buf;         // the text pugixml parses in place (names and values point here)
};

}  // namespace

XmlElement parse_xml(const std::string& text, const std::string& file) { return Reader(text, file).read(); }

XmlElement parse_xml_file(const std::string& path) {
  return parse_xml(core::read_file(path, "XML file"), path);
}

}  // namespace dp::scene
