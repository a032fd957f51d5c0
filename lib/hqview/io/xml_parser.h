#pragma once
// A small, non-validating XML parser, sufficient for VTK XML files (.vtu):
// elements, attributes (single or double quotes; the five predefined
// entities and numeric character references decoded), character data,
// comments, processing instructions, <!DOCTYPE> and CDATA sections
// (skipped). No namespaces, no DTD entities. Every element records the line
// of its '<' and its first run of character data that is not all
// whitespace (VTK writes <InformationKey> children before the values).
//
// Parsing can stop at the content of a named element (VTK's AppendedData,
// whose content is raw bytes, not XML): the document then ends there and
// stop_offset is the byte offset just after that element's start tag.
//
// Throws ParseError "name:line: message" on malformed XML: unclosed or
// mismatched tags, bad attributes, text after the root element, ...

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hqview/core/error.h"

namespace hq::detail {

struct XmlElement {
  std::string_view name;
  std::vector<std::pair<std::string_view, std::string>> attributes;  // in file order
  std::int64_t line = 0;                                             // line of the start tag's '<'
  std::string_view text;              // first run of character data directly inside (empty if none)
  std::int64_t text_line = 0;         // line where text starts
  std::size_t text_offset = 0;        // byte offset of text in the document
  std::vector<std::size_t> children;  // indices into XmlDocument::elements

  // The value of attribute `key` (exact case), nullptr when absent.
  const std::string* attribute(std::string_view key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return &v;
    return nullptr;
  }
};

struct XmlDocument {
  std::vector<XmlElement> elements;  // elements[0] is the root
  // Parsing stopped at the content of this element (npos: it did not).
  std::size_t stop_element = static_cast<std::size_t>(-1);
  std::size_t stop_offset = 0;
};

// Parses bytes (name is used in messages). stop_at: an element name whose
// content is not parsed (empty: none).
XmlDocument parse_xml(std::string_view bytes, const std::string& name, std::string_view stop_at = {});

}  // namespace hq::detail
