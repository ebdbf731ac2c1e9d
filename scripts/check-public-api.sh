#!/usr/bin/env bash
# scripts/check-public-api.sh [ROOT]: the public API is what its users call
# (issue 41; docs/architecture.md, "What is public"). Lists every function
# declared in include/ptnet/ whose only callers are its own stage (the
# stage whose HEADERS list the header, src/<stage>/CMakeLists.txt) and the
# tests, one line each (`include/ptnet/x.hpp:12: f: called only by stage
# core and tests`), and every quoted include of a public header that is not
# itself public ("core/csv.hpp": not installed), then exits 1; exits 0 when
# every function has a user. The ctest test `check_public_api` (label unit)
# runs it, so CI holds the rule.
#
# Users: app/, python/*.cpp and *.hpp, examples/, the sources and private
# headers of another stage (src/<other>/), and code in a public header
# (another stage's, or an inline body or template in its own that uses it).
# Not users: tests/, bench/ and fuzz/, which reach private headers anyway.
# Functions: what Universal Ctags lists as a prototype or function at
# namespace scope (not class members, operators or macros). A call is the
# name followed by "(" (not after "." or "->": a member's; not after a type,
# which declares a variable: `MarkerMap marker_map(...)`), a reference the
# name after "::" or after an address-of "&" (not a reference type's:
# `const std::string& marker_map` is a parameter), outside comments and
# string literals; a use in a stage that declares a function of the same
# name itself is that stage's own.
# ROOT defaults to the folder above this script.
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
if ! ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "check-public-api: needs Universal Ctags as ctags (Debian: universal-ctags)" >&2
  exit 2
fi
[ -d "$root/include/ptnet" ] || { echo "check-public-api: $root has no include/ptnet" >&2; exit 2; }
exec python3 - "$root" <<'EOF'
import glob, os, re, subprocess, sys

root = sys.argv[1]
os.chdir(root)

# The stages and the public headers each owns: ptnet_stage(NAME ... HEADERS h ...),
# by default NAME.hpp and NAME_*.hpp (cmake/ptnet.cmake).
KEYWORDS = {"SOURCES", "HEADERS", "DEPENDS", "LIBS", "TORCH"}
owner = {}  # include/ptnet/x.hpp -> stage
stages = []
for cml in sorted(glob.glob("src/*/CMakeLists.txt")):
    text = re.sub(r"#.*", "", open(cml).read())
    m = re.search(r"ptnet_stage\(\s*(\w+)([^)]*)\)", text)
    if not m:
        continue
    name, words = m.group(1), m.group(2).split()
    stages.append(name)
    headers, current = [], None
    for w in words:
        if w in KEYWORDS:
            current = w
        elif current == "HEADERS":
            headers.append("include/ptnet/%s.hpp" % w)
    if not headers:
        headers = sorted(glob.glob("include/ptnet/%s.hpp" % name) + glob.glob("include/ptnet/%s_*.hpp" % name))
    for h in headers:
        owner[h] = name

def stage_of(path):
    """The stage a file belongs to, or None (app, python, tests, ...)."""
    if path in owner:
        return owner[path]
    parts = path.split("/")
    return parts[1] if parts[0] == "src" and len(parts) > 2 and parts[1] in stages else None

def is_user_area(path):
    return path.startswith(("app/", "examples/", "src/", "include/")) or (
        path.startswith("python/") and path.endswith((".cpp", ".hpp")))

# Comments and string literals blanked (line breaks kept, so lines still count).
TOKEN = re.compile(r'//[^\n]*|/\*.*?\*/|R"([^(\s]*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)
def code_of(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    return TOKEN.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)

files = sorted(p for pattern in ("src/**/*", "include/**/*", "app/**/*", "python/**/*", "examples/**/*")
               for p in glob.glob(pattern, recursive=True)
               if p.endswith((".cpp", ".hpp", ".h", ".cc")) and is_user_area(p))
code = {p: code_of(p) for p in files}

# Every function each stage declares or defines (for same-name functions of
# two stages), and the public ones with where they are declared.
tags = subprocess.run(["ctags", "-f", "-", "--languages=C++", "--language-force=C++", "--c++-kinds=pf",
                       "--fields=+nKs", "--extras=-q"] + [p for p in files if stage_of(p)],
                      check=True, capture_output=True, text=True).stdout
declared_by = {}  # name -> stages declaring it
public = {}       # (header, name) -> declaration lines
for line in tags.splitlines():
    fields = line.split("\t")
    name, path = fields[0], fields[1]
    extra = dict(f.split(":", 1) for f in fields[3:] if ":" in f)
    scope = [k for k in extra if k in ("class", "struct", "union", "enum")]
    if scope or name.startswith(("operator", "__anon")) or name.isupper():  # (macros: TORCH_MODULE)
        continue
    declared_by.setdefault(name, set()).add(stage_of(path))
    if path in owner:
        public.setdefault((path, name), set()).add(int(extra.get("line", 0)))

# The token before position i of text: an identifier, or one character.
IDENT_END = re.compile(r"\w+$")
def token_before(text, i):
    j = i
    while j > 0 and text[j - 1].isspace():
        j -= 1
    m = IDENT_END.search(text, max(0, j - 64), j)
    return m.group(0) if m else text[j - 1:j]

# Words after which a name is an expression, not a declaration's type.
EXPRESSION_WORDS = {"return", "throw", "else", "do", "case", "co_return", "co_yield", "co_await", "new", "delete",
                    "and", "or", "not", "sizeof", "decltype", "noexcept"}
def is_type_before(token):
    """`token` ends a type (int x, MarkerMap x, std::string x): an identifier
    that is no keyword of an expression."""
    return bool(re.match(r"\w+$", token)) and not token[0].isdigit() and token not in EXPRESSION_WORDS

def is_use(text, m):
    """A call (the name and "(", not a declaration `Type name(args)`) or a
    reference (`&name` taking the address, `ns::name`); not a parameter,
    field or variable of that name (`const std::string& name`)."""
    if m.group("call") is not None:
        return not is_type_before(token_before(text, m.start()))
    if m.group("ref") == "::":
        return True
    before = token_before(text, m.start())  # before the "&": an operand or a type ends there, else it is address-of
    return not is_type_before(before) and before not in (")", "]", ">", "*", "&")

problems = []
for (header, name), lines in sorted(public.items()):
    stage = owner[header]
    # A call (the name and "(", not after "." or "->": a member's) or a
    # reference (after "&" or "::"); is_use() keeps those that are.
    n = re.escape(name)
    word = re.compile(r"(?<![\w.>])(?P<call>%s)(?=\s*\()|(?P<ref>&|::)\s*%s\b(?!\s*\()" % (n, n))
    used = False
    for path, text in code.items():
        s = stage_of(path)
        for m in word.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            if path == header and line in lines:
                continue  # the declaration itself
            if not is_use(text, m):
                continue
            if path in owner or (s != stage and s not in declared_by.get(name, set())):
                used = True  # a public header's code, another stage, app, python, examples
                break
        if used:
            break
    if not used:
        problems.append("%s:%d: %s: called only by stage %s and tests" % (header, min(lines), name, stage))

# An installed header includes only installed headers (and the system's).
for header in sorted(owner):
    for i, line in enumerate(open(header), 1):
        m = re.match(r'\s*#\s*include\s*"([^"]+)"', line)
        if m and not m.group(1).startswith("ptnet/"):
            problems.append("%s:%d: includes \"%s\", which is not installed" % (header, i, m.group(1)))

for p in problems:
    print(p)
if problems:
    print("check-public-api: %d problem(s): move a function without a user to a private header "
          "src/<stage>/*.hpp (docs/architecture.md, What is public)" % len(problems))
    sys.exit(1)
print("check-public-api: %d public functions in %d headers, each called outside its stage or by its header"
      % (len(public), len(owner)))
EOF
