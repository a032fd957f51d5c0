#include "hqview/report/link_base.h"

#include "hqview/core/error.h"
#include "hqview/report/escape.h"

namespace hq {
namespace {

bool is_relative(std::string_view target) {
  if (target.empty() || target[0] == '#' || target[0] == '/') return false;
  const std::size_t colon = target.find(':');
  const std::size_t slash = target.find('/');
  return colon == std::string_view::npos || (slash != std::string_view::npos && slash < colon);
}

// Copies `text`, inserting `base` before each relative target that follows
// one of `openers` and ends at `close`.
std::string rewrite(std::string_view text, std::initializer_list<std::string_view> openers, char close,
                    const std::string& base) {
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  std::size_t i = 0;
  while (i < text.size()) {
    std::size_t best = std::string_view::npos, best_len = 0;
    for (std::string_view o : openers)
      if (const std::size_t at = text.find(o, i); at < best) best = at, best_len = o.size();
    if (best == std::string_view::npos) break;
    const std::size_t start = best + best_len;
    const std::size_t end = text.find(close, start);
    out.append(text.substr(i, start - i));
    if (end == std::string_view::npos) {
      i = start;
      continue;
    }
    if (is_relative(text.substr(start, end - start))) out += base;
    out.append(text.substr(start, end - start));
    i = end;
  }
  out.append(text.substr(std::min(i, text.size())));
  return out;
}

}  // namespace

std::string normalize_link_base(std::string_view url) {
  const bool scheme = url.starts_with("https://") || url.starts_with("http://") || url.starts_with("file://");
  if (!scheme) throw ValueError("--link-base: '" + std::string(url) + "' must start with https://, http:// or file://");
  for (const char c : url)
    if (static_cast<unsigned char>(c) <= ' ' || c == '"' || c == '\'' || c == '<' || c == '>' || c == '(' ||
        c == ')' || c == '\\' || c == 0x7F)
      throw ValueError("--link-base: '" + std::string(url) +
                       "' holds a blank, quote, bracket or backslash; percent-encode it");
  std::string out(url);
  while (out.ends_with('/') && !out.ends_with("://")) out.pop_back();
  return out + "/";
}

std::string link_base_of(std::string_view base, std::string_view relative_dir) {
  if (base.empty()) return "";
  return std::string(base) + url_path(relative_dir) + "/";
}

std::string absolute_links_html(std::string_view html, std::string_view base) {
  if (base.empty()) return std::string(html);
  return rewrite(html, {" href=\"", " src=\""}, '"', xml_escape(base));
}

std::string absolute_links_markdown(std::string_view markdown, std::string_view base) {
  if (base.empty()) return std::string(markdown);
  return rewrite(markdown, {"]("}, ')', std::string(base));
}

}  // namespace hq
