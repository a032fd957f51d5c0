#include "hqview/io/xml_parser.h"

#include <algorithm>
#include <charconv>

#include "hqview/io/text_scanner.h"

namespace hq::detail {
namespace {

bool is_name_char(char c) {
  return !is_space(c) && c != '/' && c != '>' && c != '=' && c != '<' && c != '"' && c != '\'';
}

class XmlParser {
 public:
  XmlParser(std::string_view bytes, const std::string& name, std::string_view stop_at)
      : bytes_(bytes), name_(name), stop_at_(stop_at) {}

  XmlDocument parse() {
    std::vector<std::size_t> open;  // stack of element indices
    bool root_closed = false;
    while (true) {
      const std::size_t lt = bytes_.find('<', pos_);
      const std::string_view text =
          bytes_.substr(pos_, lt == std::string_view::npos ? std::string_view::npos : lt - pos_);
      if (open.empty()) {
        const auto bad = std::find_if(text.begin(), text.end(), [](char c) { return !is_space(c); });
        if (bad != text.end()) {
          pos_ += static_cast<std::size_t>(bad - text.begin());
          fail(root_closed ? "text after the root element" : "text before the root element");
        }
      } else {
        XmlElement& top = doc_.elements[open.back()];
        // Keep the first run that is not all whitespace: VTK writes
        // <InformationKey> children before a DataArray's values.
        const auto blank = [](std::string_view t) { return std::all_of(t.begin(), t.end(), is_space); };
        if (!text.empty() && (top.text.empty() || (blank(top.text) && !blank(text)))) {
          top.text = text;
          top.text_offset = pos_;
          top.text_line = line_at(pos_);
        }
      }
      if (lt == std::string_view::npos) {
        pos_ = bytes_.size();
        if (!open.empty())
          fail("unexpected end of file: element <" + std::string(doc_.elements[open.back()].name) + "> (line " +
               std::to_string(doc_.elements[open.back()].line) + ") is not closed");
        if (!root_closed) fail("no XML element");
        return std::move(doc_);
      }
      pos_ = lt;
      const std::string_view rest = bytes_.substr(pos_);
      if (rest.starts_with("<?")) {
        skip_past("?>", "processing instruction");
      } else if (rest.starts_with("<!--")) {
        skip_past("-->", "comment");
      } else if (rest.starts_with("<![CDATA[")) {
        if (open.empty()) fail("CDATA section outside the root element");
        skip_past("]]>", "CDATA section");
      } else if (rest.starts_with("<!")) {
        skip_past(">", "declaration");
      } else if (rest.starts_with("</")) {
        const std::size_t tag = pos_;
        pos_ += 2;
        const std::string_view closing = read_name("an element name after '</'");
        skip_spaces();
        expect('>', "'>' after </" + std::string(closing));
        if (open.empty()) fail_at(tag, "closing tag </" + std::string(closing) + "> without an open element");
        const XmlElement& top = doc_.elements[open.back()];
        if (top.name != closing)
          fail_at(tag, "closing tag </" + std::string(closing) + "> does not match <" + std::string(top.name) +
                           "> (line " + std::to_string(top.line) + ")");
        open.pop_back();
        if (open.empty()) root_closed = true;
      } else {
        if (root_closed) fail("a second root element");
        const std::size_t index = read_start_tag(open);
        if (index == static_cast<std::size_t>(-1)) {  // self-closing
          if (open.empty()) root_closed = true;
          continue;
        }
        if (doc_.elements[index].name == stop_at_ && !stop_at_.empty()) {
          doc_.stop_element = index;
          doc_.stop_offset = pos_;
          return std::move(doc_);
        }
        open.push_back(index);
      }
    }
  }

 private:
  // Reads "<name attr="v" ...>" or ".../>"; returns the element's index, or
  // npos for a self-closing element (already complete).
  std::size_t read_start_tag(const std::vector<std::size_t>& open) {
    const std::size_t tag = pos_;
    ++pos_;
    XmlElement element;
    element.line = line_at(tag);
    element.name = read_name("an element name after '<'");
    while (true) {
      const bool had_space = skip_spaces();
      if (pos_ >= bytes_.size())
        fail_at(tag, "unexpected end of file in the start tag <" + std::string(element.name) + ">");
      const char c = bytes_[pos_];
      if (c == '>' || (c == '/' && pos_ + 1 < bytes_.size() && bytes_[pos_ + 1] == '>')) {
        pos_ += c == '>' ? 1 : 2;
        const std::size_t index = doc_.elements.size();
        doc_.elements.push_back(std::move(element));
        if (!open.empty()) doc_.elements[open.back()].children.push_back(index);
        return c == '>' ? index : static_cast<std::size_t>(-1);
      }
      if (!had_space)
        fail("expected a space, '>' or '/>' in <" + std::string(element.name) + ">, got " +
             quote(bytes_.substr(pos_, 1)));
      const std::size_t attribute_pos = pos_;
      const std::string_view key = read_name("an attribute name");
      skip_spaces();
      expect('=', "'=' after attribute " + std::string(key));
      skip_spaces();
      if (pos_ >= bytes_.size() || (bytes_[pos_] != '"' && bytes_[pos_] != '\''))
        fail("expected a quoted value for attribute " + std::string(key));
      const char quote_char = bytes_[pos_++];
      const std::size_t end = bytes_.find(quote_char, pos_);
      if (end == std::string_view::npos) fail_at(attribute_pos, "unterminated value of attribute " + std::string(key));
      const std::string_view raw = bytes_.substr(pos_, end - pos_);
      if (raw.find('<') != std::string_view::npos)
        fail_at(attribute_pos, "'<' in the value of attribute " + std::string(key));
      if (element.attribute(key) != nullptr) fail_at(attribute_pos, "repeated attribute " + std::string(key));
      element.attributes.emplace_back(key, decode_entities(raw, attribute_pos));
      pos_ = end + 1;
    }
  }

  std::string decode_entities(std::string_view raw, std::size_t at) {
    std::string out;
    out.reserve(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const std::size_t semi = raw.find(';', i);
      if (semi == std::string_view::npos) fail_at(at, "unterminated entity in an attribute value");
      const std::string_view entity = raw.substr(i + 1, semi - i - 1);
      if (entity == "lt") {
        out += '<';
      } else if (entity == "gt") {
        out += '>';
      } else if (entity == "amp") {
        out += '&';
      } else if (entity == "quot") {
        out += '"';
      } else if (entity == "apos") {
        out += '\'';
      } else if (entity.size() > 1 && entity[0] == '#') {
        const bool hex = entity[1] == 'x' || entity[1] == 'X';
        const std::string_view digits = entity.substr(hex ? 2 : 1);
        unsigned code = 0;
        const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
        if (ec != std::errc{} || ptr != digits.data() + digits.size() || code == 0 || code > 0x7f)
          fail_at(at, "unsupported character reference &" + std::string(entity) + ";");
        out += static_cast<char>(code);
      } else {
        fail_at(at, "unknown entity &" + std::string(entity) + ";");
      }
      i = semi;
    }
    return out;
  }

  std::string_view read_name(const std::string& what) {
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && is_name_char(bytes_[pos_])) ++pos_;
    if (pos_ == start) fail("expected " + what + ", got " + quote(bytes_.substr(pos_, 1)));
    return bytes_.substr(start, pos_ - start);
  }
  bool skip_spaces() {
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && is_space(bytes_[pos_])) ++pos_;
    return pos_ != start;
  }
  void expect(char c, const std::string& what) {
    if (pos_ >= bytes_.size() || bytes_[pos_] != c)
      fail("expected " + what + ", got " +
           (pos_ >= bytes_.size() ? std::string("the end of the file") : quote(bytes_.substr(pos_, 1))));
    ++pos_;
  }
  void skip_past(std::string_view terminator, const std::string& what) {
    const std::size_t end = bytes_.find(terminator, pos_);
    if (end == std::string_view::npos) fail("unterminated " + what);
    pos_ = end + terminator.size();
  }

  // Lines are counted forward from the last query (queries are mostly increasing).
  std::int64_t line_at(std::size_t offset) {
    offset = std::min(offset, bytes_.size());
    if (offset < line_pos_) {
      line_pos_ = 0;
      line_ = 1;
    }
    line_ += std::count(bytes_.begin() + static_cast<std::ptrdiff_t>(line_pos_),
                        bytes_.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
    line_pos_ = offset;
    return line_;
  }
  [[noreturn]] void fail(const std::string& message) { fail_at(pos_, message); }
  [[noreturn]] void fail_at(std::size_t offset, const std::string& message) {
    throw ParseError(name_, line_at(offset), message);
  }

  std::string_view bytes_;
  const std::string& name_;
  std::string_view stop_at_;
  std::size_t pos_ = 0;
  std::size_t line_pos_ = 0;
  std::int64_t line_ = 1;
  XmlDocument doc_;
};

}  // namespace

XmlDocument parse_xml(std::string_view bytes, const std::string& name, std::string_view stop_at) {
  return XmlParser(bytes, name, stop_at).parse();
}

}  // namespace hq::detail
