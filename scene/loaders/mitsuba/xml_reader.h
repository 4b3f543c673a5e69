// A small, strict XML reader for scene files, on top of pugixml (libpugixml-dev).
// Supported: one root element, nested elements, attributes in single or double
// quotes (values verbatim apart from entities: no whitespace or line-end
// normalisation), self-closing tags, comments, the <?xml ...?> declaration (and other
// processing instructions, skipped), the five predefined entities plus decimal and
// hexadecimal character references (encoded as UTF-8). The text is taken as UTF-8
// whatever its declaration says. Rejected with a ParseError "file:line: malformed XML:
// ..." (one line; quoted input cut to ~60 characters): DOCTYPE, CDATA, non-whitespace
// text between elements, mismatched or unclosed tags, duplicate attributes, unknown
// entities, '--' inside a comment, NUL bytes, anything after the root element, and
// elements nested deeper than 256 (so that no recursive walk over the tree can
// overflow the stack). Every element records the 1-based line of its '<'.
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
