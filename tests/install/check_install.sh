#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, the prefix moved, and a full
# analysis (every view, the viewer, a reference surface) run from the moved
# copy with the source and build trees hidden (a private mount namespace
# with empty file systems over them, where the machine allows one); no
# source or build path inside the binary; the man page and the bash
# completion work; CPack's .deb holds the files and depends on Debian's
# runtime libraries (checked with dpkg-deb, not installed).
# usage: check_install.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$(cd "$1" && pwd)"
build="$(cd "$2" && pwd)"
work="$(mktemp -d /tmp/hqview-install-test.XXXXXX)"
trap 'rm -rf "$work"' EXIT
fail=0
check() { if eval "$2"; then echo "ok    $1"; else echo "FAIL  $1"; fail=1; fi; }

cmake --install "$build" --prefix "$work/prefix" >/dev/null
mv "$work/prefix" "$work/moved"
bin="$work/moved/bin/hqview"
check "installed: bin/hqview, the man page, the bash completion" \
  "[ -x '$bin' ] && [ -f '$work/moved/share/man/man1/hqview.1.gz' ] && [ -f '$work/moved/share/bash-completion/completions/hqview' ]"
mkdir "$work/in"
cp "$src/examples/ball.mesh" "$src/examples/ball.off" "$work/in/"

analyse="cd '$work' && env -i PATH=/usr/bin:/bin HOME='$work' '$bin' analyze in/ball.mesh --reference in/ball.off -o out --quiet"
if unshare --mount true 2>/dev/null; then
  # Hide the trees; the build tree may sit inside the source tree.
  hide="mount -t tmpfs none '$src'"
  case "$build" in "$src"/*) ;; *) hide="$hide && mount -t tmpfs none '$build'" ;; esac
  unshare --mount sh -c "$hide && [ -z \"\$(ls -A '$src')\" ] && $analyse"
  hidden="with the source and build trees hidden"
else
  sh -c "$analyse"
  hidden="(no mount namespace here: the trees were not hidden)"
fi
check "a full analysis from the moved prefix $hidden" \
  "[ -f '$work/out/report.json' ] && [ -f '$work/out/views/main_1.png' ] && [ -f '$work/out/viewer.html' ] && [ -f '$work/out/views/uv_error.png' ]"
check "the binary names neither the source nor the build tree" \
  "! grep -a -q -F -e '$src' -e '$build' '$bin'"
check "the man page is roff with every subcommand" \
  "zcat '$work/moved/share/man/man1/hqview.1.gz' | grep -q '^.TH HQVIEW 1' && [ \$(zcat '$work/moved/share/man/man1/hqview.1.gz' | grep -c '^.SH HQVIEW ') -eq 4 ]"
complete_words() {
  bash -c "source '$work/moved/share/bash-completion/completions/hqview'; COMP_WORDS=($1); COMP_CWORD=\$((\${#COMP_WORDS[@]} - 1)); _hqview; echo \"\${COMPREPLY[*]}\""
}
check "bash completion: subcommands, then the subcommand's flags" \
  "[ \"\$(complete_words 'hqview ba')\" = batch ] && complete_words 'hqview batch --mesh' | grep -q -- --mesh-timeout"

# The .deb (CPack; dpkg-shlibdeps gives the library dependencies).
(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/deb" >/dev/null)
deb="$(ls "$work"/deb/*.deb)"
files="$(dpkg-deb -c "$deb")"
depends="$(dpkg-deb -f "$deb" Depends)"
echo "      $(basename "$deb"): Depends: $depends"
check ".deb holds /usr/bin/hqview, the man page and the completion" \
  "grep -q ' ./usr/bin/hqview$' <<<\"\$files\" && grep -q 'share/man/man1/hqview.1.gz$' <<<\"\$files\" && grep -q 'bash-completion/completions/hqview$' <<<\"\$files\""
check ".deb depends on Debian's runtime libraries (TBB, OSMesa, libdeflate, FreeType) and the font" \
  "grep -q libtbb <<<\"\$depends\" && grep -q libosmesa6 <<<\"\$depends\" && grep -q libdeflate0 <<<\"\$depends\" && grep -q libfreetype6 <<<\"\$depends\" && grep -q fonts-dejavu-core <<<\"\$depends\" && ! grep -q -- '-dev' <<<\"\$depends\""
exit "$fail"
