#include "hqview/report/single_file.h"

#include <cctype>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/report/viewer.h"

namespace hq {
namespace {

// Which page a rewritten fragment of HTML comes from.
enum class Page { index, boundary, viewer };

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

bool has_scheme(std::string_view url) {
  std::size_t i = 0;
  while (i < url.size() && (std::isalnum(static_cast<unsigned char>(url[i])) != 0 || url[i] == '+' || url[i] == '-' ||
                            url[i] == '.'))
    ++i;
  return i > 0 && i < url.size() && url[i] == ':' && std::isalpha(static_cast<unsigned char>(url[0])) != 0;
}

// An attribute value as text: the entities the templates write decoded.
std::string unescape_attribute(std::string_view v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] == '&') {
      static constexpr std::pair<std::string_view, char> kEntities[] = {
          {"&amp;", '&'}, {"&quot;", '"'}, {"&#39;", '\''}, {"&lt;", '<'}, {"&gt;", '>'}, {"&#x27;", '\''}};
      bool done = false;
      for (const auto& [name, c] : kEntities)
        if (v.substr(i, name.size()) == name) {
          out += c;
          i += name.size() - 1;
          done = true;
          break;
        }
      if (done) continue;
    }
    out += v[i];
  }
  return out;
}

std::string escape_attribute(std::string_view v) {
  std::string out;
  out.reserve(v.size() + v.size() / 8);
  for (const char c : v) {
    if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

// A URL path's %XX decoded (the pages percent-encode file names: url_path).
std::string percent_decode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) != 0 &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2])) != 0) {
      out += static_cast<char>(std::stoi(std::string(s.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

std::string_view image_type(std::string_view path) {
  if (ends_with(path, ".png")) return "image/png";
  if (ends_with(path, ".svg")) return "image/svg+xml";
  if (ends_with(path, ".jpg") || ends_with(path, ".jpeg")) return "image/jpeg";
  return "";
}

std::string prefixed_fragment(std::string_view fragment) {
  return fragment.empty() ? "#boundary" : "#boundary-" + std::string(fragment);
}

// What becomes of one src/href value; nullopt: the attribute goes.
std::optional<std::string> rewrite_url(const SingleFileSources& s, Page page, bool is_src, const std::string& value) {
  std::string url = value;
  if (!s.link_base.empty() && starts_with(url, s.link_base)) url = url.substr(s.link_base.size());
  if (starts_with(url, "#")) {
    if (page == Page::boundary) return prefixed_fragment(url.substr(1));
    return value;
  }
  if (has_scheme(url)) return value;  // https:, mailto:, data:
  const std::size_t hash = url.find('#');
  const std::string fragment = hash == std::string::npos ? "" : url.substr(hash + 1);
  const std::string path = percent_decode(url.substr(0, hash));
  // The viewer's own links (back to the index) would load in its frame.
  if (page == Page::viewer && image_type(path).empty()) return std::nullopt;
  if (path == "index.html") return fragment.empty() ? "#" : "#" + fragment;
  if (path == "boundary.html") return prefixed_fragment(fragment);
  if (path == "viewer.html") {
    if (s.viewer_html) return std::string("#viewer");
    return std::nullopt;
  }
  if (!image_type(path).empty()) {
    if (!is_src) return std::nullopt;  // a link to the image shown right there
    const std::optional<std::string> bytes = s.read_file ? s.read_file(path) : std::nullopt;
    if (!bytes) return value;
    return "data:" + std::string(image_type(path)) + ";base64," + base64_encode(bytes->data(), bytes->size());
  }
  if (s.page_link)
    if (auto other = s.page_link(path)) return *other + (fragment.empty() ? "" : "#" + fragment);
  return value;  // a data file of the bundle, relative to report.html
}

// Every ` src="..."`, ` href="..."` (and, in the boundary section, ` id="..."`)
// of `html` rewritten.
std::string rewrite_attributes(const SingleFileSources& s, Page page, std::string_view html) {
  std::string out;
  out.reserve(html.size());
  std::size_t i = 0;
  while (i < html.size()) {
    const std::size_t at = html.find('=', i);
    if (at == std::string::npos || at + 1 >= html.size()) break;
    // The attribute name before '=', preceded by a blank; the value in double quotes.
    std::size_t name_start = at;
    while (name_start > i && std::isalpha(static_cast<unsigned char>(html[name_start - 1])) != 0) --name_start;
    const std::string_view name = html.substr(name_start, at - name_start);
    const bool known = (name == "src" || name == "href" || (name == "id" && page == Page::boundary));
    if (!known || name_start <= i || (html[name_start - 1] != ' ' && html[name_start - 1] != '\n') ||
        html[at + 1] != '"') {
      out.append(html.substr(i, at + 1 - i));
      i = at + 1;
      continue;
    }
    const std::size_t end = html.find('"', at + 2);
    if (end == std::string::npos) break;
    const std::string value = unescape_attribute(html.substr(at + 2, end - at - 2));
    std::optional<std::string> replaced;
    if (name == "id")
      replaced = "boundary-" + value;
    else
      replaced = rewrite_url(s, page, name == "src", value);
    if (replaced) {
      out.append(html.substr(i, at + 2 - i));
      out += escape_attribute(*replaced);
      out += '"';
    } else {
      out.append(html.substr(i, name_start - 1 - i));  // the attribute and its blank go
    }
    i = end + 1;
  }
  out.append(html.substr(std::min(i, html.size())));
  return out;
}

// The text between <body ...> and </body> (the whole text when absent).
std::string_view body_of(std::string_view html) {
  const std::size_t open = html.find("<body");
  const std::size_t start = open == std::string::npos ? std::string::npos : html.find('>', open);
  const std::size_t close = html.rfind("</body>");
  if (start == std::string::npos || close == std::string::npos || close < start) return html;
  return html.substr(start + 1, close - start - 1);
}

// A script's text made safe inside <script>: no "</script" can end it early.
std::string script_text(std::string_view js) {
  std::string out;
  out.reserve(js.size());
  for (std::size_t i = 0; i < js.size(); ++i) {
    if (js[i] == '<' && i + 1 < js.size() && js[i + 1] == '/' && js.size() - i >= 8) {
      std::string tag(js.substr(i + 2, 6));
      for (char& c : tag) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (tag == "script") {
        out += "<\\/";
        ++i;
        continue;
      }
    }
    out += js[i];
  }
  return out;
}

// The viewer page with its <script src="viewer/..."> inlined.
std::string inline_viewer(const SingleFileSources& s, std::string_view html) {
  std::string out;
  std::size_t i = 0;
  static constexpr std::string_view kOpen = "<script src=\"";
  while (true) {
    const std::size_t at = html.find(kOpen, i);
    const std::size_t quote = at == std::string::npos ? at : html.find('"', at + kOpen.size());
    const std::size_t close = quote == std::string::npos ? quote : html.find("</script>", quote);
    if (close == std::string::npos) break;
    const std::string path = unescape_attribute(html.substr(at + kOpen.size(), quote - at - kOpen.size()));
    const std::optional<std::string> js = s.read_file ? s.read_file(path) : std::nullopt;
    if (!js) throw Error("internal: --single-file=viewer: the viewer's script " + path + " is missing");
    out.append(html.substr(i, at - i));
    out += "<script>" + script_text(*js) + "</script>";
    i = close + std::string_view("</script>").size();
  }
  out.append(html.substr(i));
  return rewrite_attributes(s, Page::viewer, out);
}

}  // namespace

SingleFile parse_single_file(std::string_view text) {
  if (text == "pages" || text.empty()) return SingleFile::pages;
  if (text == "viewer") return SingleFile::viewer;
  throw ValueError("--single-file: '" + std::string(text) + "' (give no value, or =viewer)");
}

std::string single_file_html(const SingleFileSources& s) {
  std::string html(s.index_html);
  // The stylesheet inline (the one <link> the pages have).
  static constexpr std::string_view kLink = "<link rel=\"stylesheet\" href=\"style.css\">";
  const std::size_t link = html.find(kLink);
  if (link != std::string::npos)
    html.replace(link, kLink.size(), "<style>\n" + std::string(s.stylesheet) + "</style>");
  html = rewrite_attributes(s, Page::index, html);
  std::string sections;
  if (s.boundary_html || s.viewer_html)
    sections += "\n<style>.single-file-page{margin-top:3rem;border-top:4px solid #c8ced8}"
                "#viewer{padding:0 2rem 2rem}</style>";
  if (s.boundary_html) {
    sections += "\n<section id=\"boundary\" class=\"single-file-page\">\n";
    sections += rewrite_attributes(s, Page::boundary, body_of(*s.boundary_html));
    sections += "</section>\n";
  }
  if (s.viewer_html) {
    sections +=
        "\n<section id=\"viewer\" class=\"single-file-page\">\n<h2>Interactive 3D viewer</h2>\n"
        "<iframe title=\"HQView 3D viewer\" style=\"width:100%;height:85vh;border:1px solid #ccc\" srcdoc=\"";
    sections += escape_attribute(inline_viewer(s, *s.viewer_html));
    sections += "\"></iframe>\n</section>\n";
  }
  const std::size_t body_end = html.rfind("</body>");
  html.insert(body_end == std::string::npos ? html.size() : body_end, sections);
  return html;
}

}  // namespace hq
