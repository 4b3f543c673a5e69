// A small, strict XML reader for scene files (no XML library is a dependency).
// Supported: one root element, nested elements, attributes in single or double
// quotes, self-closing tags, comments, the <?xml ...?> declaration (and other
// processing instructions, skipped), the five predefined entities plus decimal and
// hexadecimal character references (encoded as UTF-8). Rejected with a ParseError
// carrying file and line: DOCTYPE, CDATA, non-whitespace text between elements,
// mismatched or unclosed tags, duplicate attributes, unknown entities, anything after
// the root element. Every element records the line of its '<'.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace dp::scene {

struct XmlElement {
  std::string tag;
  std::vector<std::pair<std::string, std::string>> attributes;  // in document order
  std::vector<XmlElement> children;
  std::shared_ptr<const std::string> file;  // the file this element was read from
  int line = 0;

  // Value of attribute `name`, or nullptr.
  const std::string* attribute(const std::string& name) const;
  const std::string& file_name() const;
};

// Parses `text` as read from `file` (used in error messages and XmlElement::file).
XmlElement parse_xml(const std::string& text, const std::string& file);
// Reads and parses a file; IoError if it cannot be read.
XmlElement parse_xml_file(const std::string& path);

}  // namespace dp::scene
