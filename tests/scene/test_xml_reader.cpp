// XML reader unit tests: the tree and its line numbers, every rejected construct as a
// one-line ParseError "file:line: ...", the nesting limit (50 000 nested elements are
// an error, not a stack overflow), and messages that do not echo huge input.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "core/error.h"
#include "scene/loaders/mitsuba/mitsuba_loader.h"
#include "scene/loaders/mitsuba/xml_reader.h"
#include "test_loader_util.h"

using namespace dp;
using namespace dp::scene;
using Catch::Matchers::Contains;

namespace {

void require_xml_error(const std::string& text, int line, const std::string& phrase, const std::string& path = "bad.xml") {
  require_load_error<ParseError>([](const std::string& t, const std::string& p) { return parse_xml(t, p); }, text, line, phrase,
                                 path);
}

// `n` elements <e>, each opened on its own line (line i + 1 at depth i + 1) and closed.
std::string nested(int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += "<e>\n";
  for (int i = 0; i < n; ++i) s += "</e>";
  return s;
}

}  // namespace

TEST_CASE("xml reader: elements, attributes, entities, comments, line numbers", "[unit]") {
  const std::string text =
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      "<!-- a comment with <tags> & stuff -->\n"
      "<root a=\"1\" b='x &lt; &amp;&gt; &quot;&apos; &#65;&#x42;'>\n"
      "  <child/>\n"
      "  <!-- inner -->\n"
      "  <child k=\"v\">\n"
      "    <leaf/>\n"
      "  </child>\n"
      "</root>\n";
  const XmlElement root = parse_xml(text, "t.xml");
  CHECK(root.tag == "root");
  CHECK(root.line == 3);
  REQUIRE(root.attribute("b"));
  CHECK(*root.attribute("b") == "x < &> \"' AB");
  REQUIRE(root.children.size() == 2);
  CHECK(root.children[0].line == 4);
  CHECK(root.children[1].line == 6);
  CHECK(*root.children[1].attribute("k") == "v");
  CHECK(root.children[1].children[0].tag == "leaf");
  CHECK(root.children[1].children[0].line == 7);
  CHECK(root.children[1].children[0].file_name() == "t.xml");
}

TEST_CASE("xml reader: line numbers across multi-line tags, comments, CRLF and a BOM", "[unit]") {
  const std::string text =
      "\xEF\xBB\xBF<scene\r\n"                  // 1
      "   version=\"3.0.0\">\r\n"               // 2
      "  <!-- two\r\n"                          // 3
      "       lines -->\r\n"                    // 4
      "  <a x=\"1\"\r\n"                        // 5
      "     y=\"2\"/><b/>\r\n"                  // 6
      "\r\n"                                    // 7
      "  <c v=\"multi\nline\"><d/></c>\r\n"     // 8 (the value spans 8-9)
      "<e/></scene>\r\n";                       // 10
  const XmlElement root = parse_xml(text, "t.xml");
  CHECK(root.line == 1);
  CHECK(*root.attribute("version") == "3.0.0");
  REQUIRE(root.children.size() == 4);
  CHECK(root.children[0].tag == "a");
  CHECK(root.children[0].line == 5);
  CHECK(*root.children[0].attribute("y") == "2");
  CHECK(root.children[1].line == 6);
  CHECK(root.children[2].line == 8);
  CHECK(*root.children[2].attribute("v") == "multi\nline");  // verbatim, as before
  REQUIRE(root.children[2].children.size() == 1);
  CHECK(root.children[2].children[0].line == 9);
  CHECK(root.children[3].tag == "e");
  CHECK(root.children[3].line == 10);
}

TEST_CASE("xml reader: malformed documents are ParseErrors with the line", "[unit]") {
  struct Case {
    std::string text;
    int line;
    std::string phrase;
  };
  const std::vector<Case> cases = {
      {"<a>\n<b>\n</a>", 3, "closing tag </a> does not match <b> (line 2)"},
      {"<a>\n<b x='1'/><c>\n</c>\n</d>", 4, "</d> does not match <a> (line 1)"},
      {"<a x=\"1\" x=\"2\"/>", 1, "duplicate attribute 'x' in <a>"},
      {"<a x=\"1\"\n   y=\"\" y=\"\"/>", 2, "duplicate attribute 'y'"},
      {"<a x=\"&bogus;\"/>", 1, "unknown entity '&bogus;'"},
      {"<a x=\"a\n&#0;\"/>", 2, "out of range"},
      {"<a x='<'/>", 1, "'<' inside an attribute value"},
      {"<a>\n  text\n</a>", 2, "unexpected text inside <a>"},
      {"<a>\n<b/>text<c/></a>", 2, "unexpected text inside <a>"},
      {"<a>\n<b>\n", 3, "element <b> (line 2) is never closed"},
      {"<a>\n<b/>\n", 3, "element <a> (line 1) is never closed"},
      {"<a/>\n<b/>", 2, "after the root element"},
      {"<a/>\n\n  trailing", 3, "after the root element"},
      {"<a/>x", 1, "after the root element"},
      {"<a></a>\n</a>", 2, "after the root element"},
      {"\n\ntext\n<a/>", 3, "expected the root element"},
      {"  \n", 2, "expected the root element"},
      {"<a x=1/>", 1, "must be quoted"},
      {"<a x=\"1\"y=\"2\"/>", 1, "separated by whitespace"},
      {"<!DOCTYPE x>\n<a/>", 1, "DOCTYPE"},
      {"<?xml version=\"1.0\"?>\n<!DOCTYPE\n  x>\n<a/>", 2, "DOCTYPE"},
      {"<a>\n<!DOCTYPE x></a>", 2, "DOCTYPE"},
      {"<a>\n  <![CDATA[x]]></a>", 2, "CDATA"},
      {"<a>\n  <![CDATA[]]></a>", 2, "CDATA"},
      {"<a>\n<!-- open\n", 2, "unterminated comment"},
      {"<a>\n<!-- a -- b --></a>", 2, "'--' inside a comment"},
      {std::string("<a>\n<b/>\0</a>", 13), 2, "NUL byte"},
  };
  for (const Case& c : cases) require_xml_error(c.text, c.line, c.phrase);
}

TEST_CASE("xml reader: a malformed file's error names file:line", "[unit]") {
  TempDir dir;
  const std::string path = dir.write("broken.xml", "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n</scene>\n");
  try {
    parse_xml_file(path);
    FAIL("no error");
  } catch (const ParseError& e) {
    CHECK(e.file() == path);
    CHECK(e.line() == 3);
    CHECK_THAT(std::string(e.what()), Catch::Matchers::StartsWith(path + ":3: malformed XML: closing tag </scene>"));
  }
  CHECK_THROWS_AS(parse_xml_file(dir.path("missing.xml")), IoError);
}

TEST_CASE("xml reader: nesting is limited to 256 elements, deeper input is an error and not a crash", "[unit]") {
  // 50 000 levels: a recursive parser, tree destructor or walk would overflow the stack.
  require_xml_error(nested(50000), 257, "elements nested deeper than 256", "deep.xml");
  // 256 levels are fine; the 257th element (opened on line 257) is the error.
  CHECK_NOTHROW(parse_xml(nested(256), "deep.xml"));
  require_xml_error(nested(257), 257, "elements nested deeper than 256", "deep.xml");
  // Deep and malformed: never closed, and a wrong closing tag far down.
  std::string open;
  for (int i = 0; i < 50000; ++i) open += "<e>\n";
  require_xml_error(open, 50001, "element <e> (line 50000) is never closed", "deep.xml");
  require_xml_error(open + "</f>", 50001, "</f> does not match <e> (line 50000)", "deep.xml");
  // Through the Mitsuba importer, whose walks over the tree are recursive too.
  require_load_error<ParseError>([](const std::string& t, const std::string& p) { return load_scene_mitsuba_string(t, p); },
                                 "<scene version=\"3.0.0\">\n" + nested(50000) + "</scene>", 257,
                                 "elements nested deeper than 256", "deep.xml");
}

TEST_CASE("xml reader: messages stay short on huge input", "[unit]") {
  const std::string huge(4 << 20, 'n');
  for (const std::string& text : {"<a>\n</" + huge + ">", "<" + huge + " x='1' x='2'/>", "<a>\n<" + huge + ">\n",
                                  "<a x='&" + huge + ";'/>", "<a>\n<" + huge + "\n"}) {
    try {
      parse_xml(text, "big.xml");
      FAIL("no error");
    } catch (const ParseError& e) {
      const std::string what = e.what();
      INFO(what.substr(0, 300));
      CHECK(what.size() < 300);
      CHECK(what.find('\n') == std::string::npos);
      CHECK_THAT(what, Catch::Matchers::StartsWith("big.xml:"));
    }
  }
}
