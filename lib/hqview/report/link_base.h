#pragma once
// --link-base URL: pages whose links are absolute under URL, for bundles
// published on a static site (GitHub Pages, an object store), so that
// summary.md posted as a pull-request comment or a CI job summary, far from
// the files, still links to them and shows the key image inline. Without it
// every link stays relative (the bundle opens from file://). In-page
// anchors (#quality) stay as they are.

#include <string>
#include <string_view>

namespace hq {

// URL with one trailing '/'. Throws ValueError unless it starts with
// http://, https:// or file:// and holds no blank, quote, '<', '>', '(', ')'
// or backslash (it lands in HTML attributes and Markdown link targets).
std::string normalize_link_base(std::string_view url);

// The base of a bundle at `relative_dir` (a batch's '/'-separated bundle path)
// under `base`: base + the path, percent-encoded, + '/'; empty base: empty.
std::string link_base_of(std::string_view base, std::string_view relative_dir);

// Every href="X" and src="X" of our own pages whose X is relative (no scheme,
// not '/', not '#...') becomes href="BASE X" (BASE attribute-escaped).
std::string absolute_links_html(std::string_view html, std::string_view base);

// Every Markdown link or image target "](X)" that is relative becomes
// "](BASE X)". (Text from input is Markdown-escaped, so "](" is ours.)
std::string absolute_links_markdown(std::string_view markdown, std::string_view base);

}  // namespace hq
