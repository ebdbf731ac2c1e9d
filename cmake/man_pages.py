"""Writes the man pages of the built command from its --help texts:
ptnet.1.gz and one ptnet-<command>.1.gz per subcommand (as git does).

    python3 man_pages.py PTNET VERSION OUT_DIR

Each page keeps the --help text's line breaks; option lists become tagged
paragraphs. The pages carry no date, so a rebuild gives the same bytes."""
import gzip
import os
import re
import subprocess
import sys

NAME_LINE = "PressureTransferNet: pressure-mat recordings simulated for any body and transferred between bodies"
ENTRY = re.compile(r"^  (\S.*?)(?: {2,}(\S.*))?$")  # "  --data TEXT REQUIRED        Dataset file"


def roff(text):
    """Escapes one line of text for roff."""
    text = text.replace("\\", "\\e").replace("-", "\\-")
    return "\\&" + text if text.startswith((".", "'")) else text


def indent(line):
    return len(line) - len(line.lstrip())


def text_lines(lines, base):
    """--help lines as roff text: a line continues the paragraph (roff fills
    it) unless it or the line before is indented deeper than `base`, the line
    before ends in ':', or it is a heading ("Presets:")."""
    out, previous = [], ""
    for line in lines:
        text = line.strip()
        heading = text.endswith(":") and " " not in text
        if out and (indent(line) > base or indent(previous) > base or previous.strip().endswith(":") or heading):
            out.append(".br")
        out.append(roff(text))
        previous = line
    return out


def page(name, summary, help_text, see_also):
    """One man page (roff) from a --help text."""
    out = [f'.TH {name.upper()} 1 "" "{VERSION}" "User Commands"', ".nh", ".ad l", ".SH NAME", f"{roff(name)} \\- {roff(summary)}"]
    lines = [line for line in help_text.rstrip("\n").split("\n") if line.strip()]
    usage = next(i for i, line in enumerate(lines) if line.startswith("Usage: "))
    out += [".SH SYNOPSIS", ".B " + roff(lines[usage][len("Usage: "):].strip())]
    if usage > 0:
        out += [".SH DESCRIPTION"] + text_lines(lines[:usage], 0)
    entry = []  # the current option's or subcommand's description lines
    for line in lines[usage + 1:]:
        m = ENTRY.match(line)
        if not line.startswith(" ") and line.endswith(":"):  # "Options:", "Subcommands:"
            out += text_lines(entry, indent(entry[0]) if entry else 0)
            entry = []
            out.append(".SH " + roff("COMMANDS" if line == "Subcommands:" else line[:-1].upper()))
        elif m:
            out += text_lines(entry, indent(entry[0]) if entry else 0)
            entry = [" " * 30 + m.group(2)] if m.group(2) else []
            out += [".TP", "\\fB" + roff(m.group(1)) + "\\fR"]
        else:
            entry.append(line)
    out += text_lines(entry, indent(entry[0]) if entry else 0)
    out += [".SH SEE ALSO", ", ".join(f"\\fB{roff(s)}\\fR(1)" for s in see_also),
            ".PP", "README.md and docs/ in share/doc/ptnet/ under the install prefix "
            "(/usr/share/doc/ptnet with the Debian package)."]
    return "\n".join(out) + "\n"


def help_of(*args):
    return subprocess.run([PTNET, *args, "--help"], check=True, capture_output=True, text=True).stdout


def commands(help_text):
    """(name, one-line summary) of each subcommand in the top-level --help."""
    found, in_list = [], False
    for line in help_text.split("\n"):
        if line == "Subcommands:":
            in_list = True
        elif in_list and ENTRY.match(line) and ENTRY.match(line).group(2):
            found.append([ENTRY.match(line).group(1), ENTRY.match(line).group(2)])
        elif in_list and line.startswith("    ") and found:
            found[-1][1] += " " + line.strip()
    return [(name, short(text)) for name, text in found]


def short(text):
    """The summary's first phrase: up to '. ', '; ', ' (' or, after four words, ': '."""
    cut = min((i for i in (text.find(". "), text.find("; "), text.find(" (")) if i > 0), default=len(text))
    colon = text.find(": ")
    if 0 < colon < cut and len(text[:colon].split()) >= 4:
        cut = colon
    return text[:cut].rstrip(".")


def write(path, text):
    with open(path, "wb") as f, gzip.GzipFile(filename="", mode="wb", fileobj=f, mtime=0) as z:
        z.write(text.encode())


if __name__ == "__main__":
    PTNET, VERSION, OUT = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(OUT, exist_ok=True)
    top = help_of()
    subs = commands(top)
    for name, summary in subs:
        write(os.path.join(OUT, f"ptnet-{name}.1.gz"), page(f"ptnet-{name}", summary, help_of(name), ["ptnet"]))
    write(os.path.join(OUT, "ptnet.1.gz"), page("ptnet", NAME_LINE, top, [f"ptnet-{n}" for n, _ in subs]))
