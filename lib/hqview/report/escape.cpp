#include "hqview/report/escape.h"

#include <cctype>

#include <nlohmann/json.hpp>

#include "hqview/core/message_text.h"

namespace hq {
namespace {

// The five characters with a meaning in XML and HTML markup as entities (the
// set mustache's own escape writes): true when c was one.
bool append_entity(std::string& out, char c) {
  switch (c) {
    case '&': out += "&amp;"; return true;
    case '<': out += "&lt;"; return true;
    case '>': out += "&gt;"; return true;
    case '"': out += "&quot;"; return true;
    case '\'': out += "&apos;"; return true;
    default: return false;
  }
}

}  // namespace

std::string markdown_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : message_text(text)) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (u < 0x20 || u == 0x7f)
      out += ' ';
    else if (u < 0x80 && std::ispunct(u)) {
      out += '\\';
      out += c;
    } else {
      out += c;
    }
  }
  return out;
}

std::string url_path(std::string_view path) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char c : path) {
    const auto b = static_cast<unsigned char>(c);
    if (std::isalnum(b) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/') {
      out += c;
    } else {
      out += '%';
      out += kHex[b >> 4];
      out += kHex[b & 15];
    }
  }
  return out;
}

std::string xml_escape(std::string_view text) {
  const std::string message = message_text(text, LineBreaks::kept);
  std::string out;
  out.reserve(message.size());
  for (std::size_t i = 0; i < message.size(); ++i) {
    const char c = message[i];
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(message[k]); };
    if (append_entity(out, c)) continue;
    if (c == '\n') {
      out += "&#10;";
    } else if (byte(i) == 0xEF && i + 2 < message.size() && byte(i + 1) == 0xBF &&
               (byte(i + 2) == 0xBE || byte(i + 2) == 0xBF)) {
      // U+FFFE and U+FFFF (EF BF BE, EF BF BF): valid UTF-8, not XML 1.0 characters.
      out += byte(i + 2) == 0xBE ? "\\xef\\xbf\\xbe" : "\\xef\\xbf\\xbf";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : message_text(text))
    if (!append_entity(out, c)) out += c;
  return out;
}

template <class Json>
Json json_message_text(const Json& value) {
  if (value.is_string()) return message_text(value.template get_ref<const typename Json::string_t&>());
  if (value.is_array()) {
    Json out = Json::array();
    for (const Json& element : value) out.push_back(json_message_text(element));
    return out;
  }
  if (value.is_object()) {
    Json out = Json::object();
    for (auto it = value.begin(); it != value.end(); ++it) out[message_text(it.key())] = json_message_text(it.value());
    return out;
  }
  return value;
}

template nlohmann::json json_message_text(const nlohmann::json&);
template nlohmann::ordered_json json_message_text(const nlohmann::ordered_json&);


std::string latex_escape(std::string_view text) {
  std::string out;
  for (char ch : message_text(text)) {
    switch (ch) {
      case '\\': out += "\\textbackslash{}"; break;
      case '{': out += "\\{"; break;
      case '}': out += "\\}"; break;
      case '$': out += "\\$"; break;
      case '&': out += "\\&"; break;
      case '#': out += "\\#"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '_': out += "\\_"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '%': out += "\\%"; break;
      default: out += ch;
    }
  }
  return out;
}

}  // namespace hq
