#!/usr/bin/env python3
"""The man page (hqview.1.gz) and the bash completion (hqview.bash), both
generated from hqview's own --help text, so they never drift from the CLI.

usage: make_docs_from_help.py HQVIEW MAN_OUT COMPLETION_OUT
"""
import gzip
import re
import subprocess
import sys

SUBCOMMANDS = ["analyze", "batch", "merge", "diff"]


def help_of(hqview, *args):
    out = subprocess.run([hqview, *args, "--help"], capture_output=True, text=True, check=True).stdout
    return out.replace(hqview, "hqview")


def sections(text):
    """{'Options': [(flags, arg, description)], 'Positionals': [...]} and the summary line."""
    summary = text.splitlines()[0].strip()
    current, out = None, {}
    entry = None
    for line in text.splitlines()[1:]:
        if re.match(r"^[A-Z][A-Za-z ]*:$", line):
            current = line[:-1]
            out[current] = []
            continue
        if current is None or not line.strip():
            continue
        m = re.match(r"^  (\S.*?)(?:\s{2,}(.*))?$", line)
        if m and not line.startswith("    "):
            spec, desc = m.group(1), m.group(2) or ""
            entry = [spec, desc]
            out[current].append(entry)
        elif entry is not None:
            entry[1] = (entry[1] + " " + line.strip()).strip()
    return summary, out


def roff(text):
    text = text.replace("\\", "\\e").replace("-", "\\-")
    return "\\&" + text if text.startswith((".", "'")) else text


def flags_of(spec):
    """'-o,--output TEXT REQUIRED' -> ['-o', '--output'], 'TEXT REQUIRED'."""
    head, _, rest = spec.partition(" ")
    return [f for f in head.split(",") if f.startswith("-")], rest


def man_page(hqview):
    version = subprocess.run([hqview, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    lines = [
        '.TH HQVIEW 1 "" "%s" "User Commands"' % roff(version),
        ".SH NAME",
        "hqview \\- hexahedral mesh quality analysis and report bundles",
        ".SH SYNOPSIS",
    ]
    for sub in SUBCOMMANDS:
        usage = [l for l in help_of(hqview, sub).splitlines() if l.startswith("Usage:")][0]
        lines += [".PP", ".B " + roff(usage[len("Usage: "):].strip())]
    lines += [".SH DESCRIPTION",
              "HQView analyses the quality of hexahedral meshes (per-corner scaled Jacobian and the Verdict hex "
              "metrics, glyphs, overlapping vertices and intersecting cells, boundary error against a reference "
              "surface) and writes a static report bundle: HTML, PNG/SVG, JSON, CSV, VTU. The full manual is the "
              "README; the exact contract is docs/contract.md."]
    for sub in [None] + SUBCOMMANDS:
        summary, secs = sections(help_of(hqview, *([sub] if sub else [])))
        lines.append(".SH " + ("OPTIONS" if sub is None else "HQVIEW " + sub.upper()))
        if sub:
            lines += [roff(summary) + "."]
        for name in ["Positionals", "Options"]:
            for spec, desc in secs.get(name, []):
                lines += [".TP", ".B " + roff(spec), roff(desc)]
    lines += [".SH EXIT STATUS",
              ".TP", "0", "analysis done, every gate passed",
              ".TP", "1", "analysis done, a gate failed",
              ".TP", "2", "usage error: bad flag or value, refused output directory",
              ".TP", "3", "input error: unreadable or malformed file (path:line: what is wrong); batch: a mesh failed",
              ".TP", "4", "internal error (a bug: please report it)",
              ".TP", "5", "environment failure: no space left, file too large, read-only or permission denied",
              ".TP", "130, 143", "stopped by SIGINT, SIGTERM",
              ".SH SEE ALSO", "docs/contract.md, docs/collections.md of the HQView sources."]
    return "\n".join(lines) + "\n"


def completion(hqview):
    cases = []
    for sub in SUBCOMMANDS:
        _, secs = sections(help_of(hqview, sub))
        flags, files = [], []
        for spec, _ in secs.get("Options", []):
            names, arg = flags_of(spec)
            flags += names
            if arg and not re.match(r"^(INT|FLOAT)", arg):
                files += names
        cases.append((sub, flags, files))
    out = ["# bash completion for hqview (generated from `hqview --help` by cmake/make_docs_from_help.py)",
           "_hqview() {",
           "  local cur prev sub i",
           "  cur=\"${COMP_WORDS[COMP_CWORD]}\"",
           "  prev=\"${COMP_WORDS[COMP_CWORD-1]}\"",
           "  sub=\"\"",
           "  for ((i = 1; i < COMP_CWORD; i++)); do",
           "    case \"${COMP_WORDS[i]}\" in %s) sub=\"${COMP_WORDS[i]}\"; break;; esac" % "|".join(SUBCOMMANDS),
           "  done",
           "  if [ -z \"$sub\" ]; then",
           "    COMPREPLY=($(compgen -W \"%s --help --version\" -- \"$cur\"))" % " ".join(SUBCOMMANDS),
           "    return",
           "  fi",
           "  case \"$sub\" in"]
    for sub, flags, files in cases:
        out += ["    %s)" % sub]
        if files:
            out += ["      case \"$prev\" in %s) COMPREPLY=($(compgen -f -- \"$cur\")); compopt -o filenames 2>/dev/null; return;; esac"
                    % "|".join(files)]
        out += ["      if [[ \"$cur\" == -* ]]; then",
                "        COMPREPLY=($(compgen -W \"%s\" -- \"$cur\"))" % " ".join(flags),
                "      else",
                "        COMPREPLY=($(compgen -f -- \"$cur\")); compopt -o filenames 2>/dev/null",
                "      fi",
                "      ;;"]
    out += ["  esac", "}", "complete -F _hqview hqview", ""]
    return "\n".join(out)


def main():
    hqview, man_out, completion_out = sys.argv[1:4]
    with open(man_out, "wb") as f:
        # mtime 0: the same bytes on every build.
        f.write(gzip.compress(man_page(hqview).encode(), mtime=0))
    with open(completion_out, "w") as f:
        f.write(completion(hqview))


if __name__ == "__main__":
    main()
