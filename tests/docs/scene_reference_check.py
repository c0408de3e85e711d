#!/usr/bin/env python3
"""Checks docs/scene-reference.md against the scene reader.

Usage: scene_reference_check.py REPO_ROOT

The reader (io/scene.cpp, io/scene_sections.cpp, io/scene_cursor.h) accepts exactly the keys
of the lists passed to Cursor::map({...}): every other key of that map is an "unknown key"
error. This script finds those lists in the comment-stripped sources and works out the key
path of each map by following the cursors through the code: `X.at("k")`, `X.get("k")`,
`X.items()`, `entries()`, local variables, lambda parameters (forEachItem, valueOr), and the
cursor arguments of calls to other reader functions, starting from the root cursor that
parseScene builds. Key paths are compared without list / name-map levels
(`analysis.rqd.balls[].name` -> `analysis.rqd.balls.name`, `materials.<name>.young` ->
`materials.young`). Only string literals in key positions are read (map lists and the key
arguments of the cursor's key getters), never message strings.

The page documents a key as the first column of a table whose header starts with "key",
under a heading that names the section (## `loads`, ### `analysis.rqd` (extension),
"## Top level"); a paragraph "Each `water` entry:" puts the next table under that key. A row
whose type is a distribution takes the keys of "## Distributions"; a row that links to a
section of the page (`[joints](#joints)`) takes that section's keys. A key is also mentioned
(enough for the accepted -> documented direction, not documented for the other one) in a
`{a, b}` / `{a: ..., b: ...}` of the type column or of a section's prose, and as a backticked
name in the checks column of a row of type "map".

Exit status: 0 when every accepted key is mentioned and every documented key is accepted,
1 when not (each one listed), 2 when the sources or the page cannot be read as expected.
"""

import os
import re
import sys

READER_SOURCES = ["io/scene_cursor.h", "io/scene_sections.cpp", "io/scene_uncertainty.cpp",
                  "io/scene.cpp"]
CURSOR_HEADER = "io/scene_cursor.h"
PAGE = "docs/scene-reference.md"

# Exceptions: none needed. Add entries here as "normalized.key.path": "reason" only for a
# difference the extraction cannot see (for instance a key read through a string variable).
ACCEPTED_NOT_DOCUMENTED_OK = {}
DOCUMENTED_NOT_ACCEPTED_OK = {}

IDENT = r"[A-Za-z_]\w*"
KEYWORDS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype",
            "static_assert", "alignof", "noexcept", "throw", "new", "delete"}


class ScriptError(Exception):
    """The sources or the page do not look as this script expects (exit 2)."""


# -------------------------------------------------------------------------------------------
# C++ text: comments removed, literals masked
# -------------------------------------------------------------------------------------------

def strip_comments(text):
    """The text with comments replaced by spaces (newlines kept) and the text with, in
    addition, the contents of string and character literals replaced by '_' (quotes kept):
    structure is scanned on the second, literals read from the first, at the same offsets."""
    code, masked = [], []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            code.append(" " * (j - i)); masked.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            blank = re.sub(r"[^\n]", " ", text[i:j])
            code.append(blank); masked.append(blank); i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                code.append(c); masked.append(c); i += 1; continue
            end = text.find(")" + m.group(1) + '"', i)
            end = n if end < 0 else end + len(m.group(1)) + 2
            code.append(text[i:end])
            masked.append('"' + re.sub(r"[^\n]", "_", text[i + 1:end - 1]) + '"')
            i = end
        elif c in "\"'":
            if c == "'" and re.search(r"\b\d[\w']*$", text[max(0, i - 40):i]):
                # digit separator (1'000)
                code.append(c); masked.append(c); i += 1; continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(j, n - 1)
            code.append(text[i:j + 1])
            masked.append(c + "_" * (j - i - 1) + c)
            i = j + 1
        else:
            code.append(c); masked.append(c); i += 1
    return "".join(code), "".join(masked)


OPEN, CLOSE = "([{", ")]}"


def match_forward(masked, i):
    """Index of the bracket that closes the one at i."""
    depth = 0
    for j in range(i, len(masked)):
        if masked[j] in OPEN:
            depth += 1
        elif masked[j] in CLOSE:
            depth -= 1
            if depth == 0:
                return j
    raise ScriptError("unbalanced bracket at offset %d" % i)


def match_backward(masked, i):
    """Index of the bracket that opens the one that closes at i."""
    depth = 0
    for j in range(i, -1, -1):
        if masked[j] in CLOSE:
            depth += 1
        elif masked[j] in OPEN:
            depth -= 1
            if depth == 0:
                return j
    raise ScriptError("unbalanced bracket at offset %d" % i)


def split_args(masked, open_paren):
    """(start, end) of each top-level argument of the call whose '(' is at open_paren."""
    close = match_forward(masked, open_paren)
    args, depth, start = [], 0, open_paren + 1
    for j in range(open_paren + 1, close):
        ch = masked[j]
        if ch in OPEN:
            depth += 1
        elif ch in CLOSE:
            depth -= 1
        elif ch == "," and depth == 0:
            args.append((start, j)); start = j + 1
    if masked[start:close].strip():
        args.append((start, close))
    return args


def skip_ws(masked, i):
    while i < len(masked) and masked[i].isspace():
        i += 1
    return i


def skip_ws_back(masked, i):
    while i >= 0 and masked[i].isspace():
        i -= 1
    return i


class Source:
    def __init__(self, path, rel):
        with open(path, encoding="utf-8") as f:
            self.text = f.read()
        self.rel = rel
        self.code, self.masked = strip_comments(self.text)

    def literal(self, start, end):
        """The value of the string literal that spans [start, end) (whitespace around it
        allowed), or None when the text there is not one plain string literal."""
        s = skip_ws(self.masked, start)
        e = skip_ws_back(self.masked, end - 1) + 1
        if e - s >= 2 and self.masked[s] == '"' and self.masked[e - 1] == '"' and \
                '"' not in self.masked[s + 1:e - 1]:
            return self.code[s + 1:e - 1]
        return None

    def line(self, offset):
        return self.text.count("\n", 0, offset) + 1


# -------------------------------------------------------------------------------------------
# The cursor's key getters (from io/scene_cursor.h)
# -------------------------------------------------------------------------------------------

def key_getters(header):
    """{name: (is_method, [argument index of each key])}: the functions of the cursor header
    that take a key name, i.e. a std::string_view parameter called key, first or second
    (has, get, at, oneOf, valueOr, numberOr, integerOr, forEachItem). The first item is
    None for a Cursor method (the receiver is the object), and for a free function the
    index of its `const Cursor&` argument (the receiver)."""
    getters = {}
    masked = header.masked
    class_match = re.search(r"\bclass\s+Cursor\b[^{;]*\{", masked)
    if not class_match:
        raise ScriptError("%s: no class Cursor" % header.rel)
    class_open = class_match.end() - 1
    class_close = match_forward(masked, class_open)
    for m in re.finditer(r"\b(%s)\s*\(" % IDENT, masked):
        name = m.group(1)
        if name in KEYWORDS:
            continue
        open_paren = m.end() - 1
        params = [masked[s:e].strip() for s, e in split_args(masked, open_paren)]
        keys = [i for i, p in enumerate(params)
                if re.fullmatch(r"std::string_view\s+(key|first|second)", p)]
        if not keys:
            continue
        after = skip_ws(masked, match_forward(masked, open_paren) + 1)
        if not re.match(r"(const\s*)?\{", masked[after:]):
            continue  # a call, not a definition
        inside_class = class_open < m.start() < class_close
        if inside_class:
            getters[name] = (None, keys)
        else:
            cursor = [i for i, p in enumerate(params) if re.fullmatch(r"const\s+Cursor\s*&\s*\w+", p)]
            if not cursor:
                continue
            getters[name] = (cursor[0], keys)
    for needed in ("at", "get"):
        if needed not in getters:
            raise ScriptError("%s: Cursor has no key getter '%s'" % (header.rel, needed))
    if "map" not in re.findall(r"\bCursor\s+(map)\s*\(", masked):
        raise ScriptError("%s: Cursor has no map(allowed keys)" % header.rel)
    return getters


# -------------------------------------------------------------------------------------------
# Reader functions and the paths of their cursors
# -------------------------------------------------------------------------------------------

class Function:
    def __init__(self, source, name, params, body_open, body_close):
        self.source = source
        self.name = name
        self.cursor_params = {}  # index -> parameter name
        for index, param in enumerate(params):
            m = re.fullmatch(r"(?:const\s+)?Cursor\s*&?\s*(\w+)", param)
            if m:
                self.cursor_params[index] = m.group(1)
        self.body_open, self.body_close = body_open, body_close
        self.param_paths = {index: set() for index in self.cursor_params}


def find_functions(source):
    masked = source.masked
    functions = []
    for m in re.finditer(r"\b(%s)\s*\(" % IDENT, masked):
        name = m.group(1)
        if name in KEYWORDS:
            continue
        before = skip_ws_back(masked, m.start() - 1)
        if before >= 0 and (masked[before] == "." or masked.startswith("->", before - 1)):
            continue  # a method call (x.f(), x->f())
        open_paren = m.end() - 1
        close = match_forward(masked, open_paren)
        after = skip_ws(masked, close + 1)
        tail = re.match(r"(?:(?:const|override|noexcept|final)\s*)*\{", masked[after:])
        if not tail:
            continue
        body_open = after + tail.end() - 1
        params = [masked[s:e].strip() for s, e in split_args(masked, open_paren)]
        functions.append(Function(source, name, params, body_open,
                                  match_forward(masked, body_open)))
    # A member initializer such as `mark_(...) {}` is matched too; it holds nothing.
    return functions


def enclosing_block_end(masked, pos, lo):
    """End of the innermost { } block (after lo) that contains pos."""
    depth = 0
    for j in range(pos, -1, -1):
        if j < lo:
            break
        ch = masked[j]
        if ch == "}":
            depth += 1
        elif ch == "{":
            if depth == 0:
                return match_forward(masked, j)
            depth -= 1
    return None


def statement_end(masked, pos):
    """End of the statement that starts at pos: its { } block, or its ';'."""
    pos = skip_ws(masked, pos)
    if masked[pos] == "{":
        return match_forward(masked, pos)
    depth = 0
    for j in range(pos, len(masked)):
        ch = masked[j]
        if ch in OPEN:
            depth += 1
        elif ch in CLOSE:
            depth -= 1
        elif ch == ";" and depth == 0:
            return j
    return len(masked) - 1


def expression_end(masked, pos):
    """End of an initializer expression that starts at pos (before a ';', ',' or an
    unmatched ')')."""
    depth = 0
    for j in range(pos, len(masked)):
        ch = masked[j]
        if ch in OPEN:
            depth += 1
        elif ch in CLOSE:
            if depth == 0:
                return j
            depth -= 1
        elif ch in ";," and depth == 0:
            return j
    return len(masked)


class Binding:
    def __init__(self, name, start, end, expr=None, paths=None, key_extra=None):
        self.name, self.start, self.end = name, start, end
        self.expr = expr            # (start, end) of an expression to evaluate at `start`
        self.paths = paths          # or fixed paths
        self.key_extra = key_extra  # (receiver expr, key, suffix): receiver paths + key + suffix


class Analysis:
    def __init__(self, sources, getters):
        self.sources = sources
        self.getters = getters
        self.functions = [f for s in sources for f in find_functions(s)]
        self.by_name = {}
        for f in self.functions:
            if f.cursor_params:
                self.by_name.setdefault(f.name, []).append(f)
        self.bindings = {id(f): self.find_bindings(f) for f in self.functions}

    # ----- bindings of cursor variables in a function body -----

    def find_bindings(self, f):
        s, masked = f.source, f.source.masked
        lo, hi = f.body_open, f.body_close
        body = masked[lo:hi]
        bindings = []
        for index, name in f.cursor_params.items():
            bindings.append(Binding(name, lo, hi, paths=("param", index)))
        # const Cursor x = ...; const auto x = ...; std::optional<Cursor> x = ...; in an
        # if (...) header too.
        for m in re.finditer(r"(?<![\w:])(?:const\s+)?(?:Cursor|auto|std::optional<Cursor>)\s+(\w+)\s*=(?!=)", body):
            start = lo + m.start()
            expr_start = lo + m.end()
            expr_end = expression_end(masked, expr_start)
            bindings.append(Binding(m.group(1), start, self.scope_end(masked, start, lo, hi),
                                    expr=(expr_start, expr_end)))
        # const Cursor x(source, node, "path", mark): a cursor made with a literal path.
        for m in re.finditer(r"(?<![\w:])(?:const\s+)?Cursor\s+(\w+)\s*\(", body):
            start = lo + m.start()
            args = split_args(masked, lo + m.end() - 1)
            path = s.literal(*args[2]) if len(args) >= 3 else None
            paths = {tuple(path.split("."))} if path else ({()} if path == "" else set())
            bindings.append(Binding(m.group(1), start, self.scope_end(masked, start, lo, hi),
                                    paths=paths))
        # for (const auto& [name, x] : ...) / for (const Cursor& x : ...)
        for m in re.finditer(r"\bfor\s*\(\s*const\s+(?:auto|Cursor)\s*&\s*(?:\[\s*\w+\s*,\s*(\w+)\s*\]|(\w+))\s*:", body):
            header_open = lo + m.start() + m.group(0).index("(")
            header_close = match_forward(masked, header_open)
            bindings.append(Binding(m.group(1) or m.group(2), lo + m.start(),
                                    statement_end(masked, header_close + 1),
                                    expr=(lo + m.end(), header_close)))
        # [..](const Cursor& x) { ... } passed to forEachItem(m, "key", ...) or
        # m.valueOr("key", fallback, ...)
        for m in re.finditer(r"\[[^\]\[]*\]\s*\(\s*const\s+Cursor\s*&\s*(\w+)\s*\)\s*(?:->\s*[\w:<>]+\s*)?\{", body):
            lambda_start = lo + m.start()
            body_open = lo + m.end() - 1
            bindings.append(Binding(m.group(1), lambda_start, match_forward(masked, body_open),
                                    key_extra=self.lambda_context(s, lambda_start)))
        bindings.sort(key=lambda b: b.start)
        return bindings

    @staticmethod
    def scope_end(masked, start, lo, hi):
        """A declaration in an if/for/while header lives for the controlled statement, any
        other until the end of its block."""
        before = skip_ws_back(masked, start - 1)
        if masked[before] == "(":
            keyword = re.search(r"\b(if|for|while|switch)\s*$", masked[lo:before])
            if keyword:
                close = match_forward(masked, before)
                return statement_end(masked, close + 1)
        end = enclosing_block_end(masked, start, lo)
        return hi if end is None else end

    def lambda_context(self, s, lambda_start):
        """(receiver expression, key, suffix) of the call a lambda is passed to, when that is a
        key getter (valueOr: the lambda reads receiver.key) or forEachItem (each item of the
        list receiver.key)."""
        masked = s.masked
        depth, j = 0, lambda_start - 1
        while j >= 0:
            ch = masked[j]
            if ch in CLOSE:
                depth += 1
            elif ch in OPEN:
                if depth == 0:
                    break
                depth -= 1
            j -= 1
        if j < 0 or masked[j] != "(":
            return None
        call = re.search(r"(\w+)\s*$", masked[:j])
        if not call or call.group(1) not in self.getters:
            return None
        args = split_args(masked, j)
        cursor_index, key_indexes = self.getters[call.group(1)]
        if cursor_index is None:
            receiver = self.receiver_before(s, call.start(1))
            suffix = ()
        else:
            receiver = args[cursor_index] if cursor_index < len(args) else None
            suffix = ("[]",)  # forEachItem: each item of the list
        key = s.literal(*args[key_indexes[0]]) if key_indexes[0] < len(args) else None
        if receiver is None or key is None:
            return None
        return (receiver, key, suffix)

    @staticmethod
    def receiver_before(s, name_start):
        """(start, end) of the receiver expression of the method call whose name starts at
        name_start (`x.at("k").name(...)` -> `x.at("k")`), or None when it is no method call."""
        masked = s.masked
        j = skip_ws_back(masked, name_start - 1)
        if masked[j] == ".":
            end = j
        elif masked[j] == ">" and masked[j - 1] == "-":
            end = j - 1
        else:
            return None
        k = end - 1
        while True:
            k = skip_ws_back(masked, k)
            if masked[k] == ")":
                open_paren = match_backward(masked, k)
                ident = re.search(r"(\w+)\s*$", masked[:open_paren])
                if not ident:
                    start = open_paren
                else:
                    start = ident.start(1)
            elif masked[k].isalnum() or masked[k] == "_":
                start = re.search(r"(\w+)$", masked[:k + 1]).start(1)
            else:
                return None
            p = skip_ws_back(masked, start - 1)
            if masked[p] == ".":
                k = p - 1
                continue
            if masked[p] == ">" and masked[p - 1] == "-":
                k = p - 2
                continue
            if masked[p] == "*":
                q = skip_ws_back(masked, p - 1)
                if not (masked[q].isalnum() or masked[q] in "_)]"):
                    start = p
            return (start, end)

    # ----- evaluating cursor expressions -----

    def resolve(self, f, name, pos, memo):
        best = None
        for b in self.bindings[id(f)]:
            if b.name == name and b.start <= pos <= b.end and b.start < pos:
                best = b
        if best is None:
            return set()
        key = id(best)
        if key in memo:
            return memo[key]
        memo[key] = set()  # no cycles
        if isinstance(best.paths, tuple) and best.paths and best.paths[0] == "param":
            result = set(f.param_paths[best.paths[1]])
        elif best.paths is not None:
            result = set(best.paths)
        elif best.expr is not None:
            result = self.evaluate(f, best.expr[0], best.expr[1], memo)
        elif best.key_extra is not None:
            (rs, re_), key_name, suffix = best.key_extra
            result = {p + (key_name,) + suffix for p in self.evaluate(f, rs, re_, memo)}
        else:
            result = set()
        memo[key] = result
        return result

    def evaluate(self, f, start, end, memo):
        """Key paths the cursor expression masked[start:end] may stand for (empty: not a
        cursor, or not known)."""
        s, masked = f.source, f.source.masked
        i = skip_ws(masked, start)
        if i < end and masked[i] == "*":
            i = skip_ws(masked, i + 1)
        m = re.compile(IDENT).match(masked, i, end)
        if not m:
            return set()
        name = m.group(0)
        i = skip_ws(masked, m.end())
        if i < end and masked[i] == "(":
            return set()  # a call: not a cursor variable
        paths = self.resolve(f, name, m.start(), memo)
        while True:
            i = skip_ws(masked, i)
            if i >= end or not paths:
                break
            if masked.startswith("->", i):
                i += 2
            elif masked[i] == ".":
                i += 1
            else:
                return set()  # anything else (an operator, an index): not a plain cursor
            method = re.compile(IDENT).match(masked, skip_ws(masked, i), end)
            if not method:
                return set()
            i = skip_ws(masked, method.end())
            if i >= end or masked[i] != "(":
                return set()
            close = match_forward(masked, i)
            args = split_args(masked, i)
            name = method.group(0)
            if name in ("at", "get"):
                key = s.literal(*args[0]) if args else None
                if key is None:
                    return set()
                paths = {p + (key,) for p in paths}
            elif name in ("map", "value", "value_or"):
                pass
            elif name == "items":
                paths = {p + ("[]",) for p in paths}
            elif name == "entries":
                paths = {p + ("*",) for p in paths}
            elif name == "valueOr" and len(args) == 3 and \
                    re.fullmatch(r"\s*&\s*Cursor\s*::\s*entries\s*", masked[args[2][0]:args[2][1]]):
                key = s.literal(*args[0])
                if key is None:
                    return set()
                paths = {p + (key, "*") for p in paths}
            else:
                return set()
            i = close + 1
        return paths

    # ----- the walk -----

    def walk(self, f, memo, record):
        """Propagates cursor paths into the reader functions f calls; with record, returns
        the map lists and key reads of f."""
        s, masked = f.source, f.source.masked
        lo, hi = f.body_open, f.body_close
        changed = False
        maps, reads, unresolved = [], [], []
        # Calls of reader functions: f2(cursor, ...); m.valueOr("key", x, &f2).
        for m in re.finditer(r"\b(%s)\s*\(" % IDENT, masked[lo:hi]):
            callees = self.by_name.get(m.group(1))
            if not callees:
                continue
            args = split_args(masked, lo + m.end() - 1)
            for callee in callees:
                for index in callee.cursor_params:
                    if index < len(args):
                        new = self.evaluate(f, args[index][0], args[index][1], memo)
                        if not new <= callee.param_paths[index]:
                            callee.param_paths[index] |= new
                            changed = True
        for m in re.finditer(r"(?:\.|->)\s*(valueOr)\s*\(", masked[lo:hi]):
            open_paren = lo + m.end() - 1
            args = split_args(masked, open_paren)
            if len(args) != 3:
                continue
            pointer = re.fullmatch(r"\s*&\s*(\w+)\s*", masked[args[2][0]:args[2][1]])
            key = s.literal(*args[0])
            receiver = self.receiver_before(s, lo + m.start(1))
            if not pointer or key is None or receiver is None:
                continue
            paths = {p + (key,) for p in self.evaluate(f, receiver[0], receiver[1], memo)}
            for callee in self.by_name.get(pointer.group(1), []):
                index = min(callee.cursor_params)
                if not paths <= callee.param_paths[index]:
                    callee.param_paths[index] |= paths
                    changed = True
        if not record:
            return changed
        # Allowed-key lists: receiver.map({"a", "b", ...}).
        for m in re.finditer(r"(?:\.|->)\s*map\s*\(", masked[lo:hi]):
            open_paren = lo + m.end() - 1
            name_start = lo + m.start() + m.group(0).index("map")
            receiver = self.receiver_before(s, name_start)
            args = split_args(masked, open_paren)
            if len(args) != 1:
                continue
            a0, a1 = args[0]
            a0 = skip_ws(masked, a0)
            if masked[a0] != "{":
                unresolved.append(("map list not literal", s.line(a0)))
                continue
            items = split_args(masked, a0)  # the { } works as a bracket
            keys = [s.literal(x, y) for x, y in items]
            if any(k is None for k in keys):
                raise ScriptError("%s:%d: a map list holds something other than string "
                                  "literals" % (s.rel, s.line(a0)))
            paths = self.evaluate(f, receiver[0], receiver[1], memo) if receiver else set()
            maps.append((paths, keys, s.rel, s.line(a0)))
        # Keys read by the getters (checked against the lists).
        for name, (cursor_index, key_indexes) in self.getters.items():
            for m in re.finditer(r"\b%s\s*\(" % re.escape(name), masked[lo:hi]):
                open_paren = lo + m.end() - 1
                args = split_args(masked, open_paren)
                if cursor_index is None:
                    receiver = self.receiver_before(s, lo + m.start())
                else:
                    receiver = args[cursor_index] if cursor_index < len(args) else None
                if receiver is None:
                    continue
                paths = self.evaluate(f, receiver[0], receiver[1], memo)
                for index in key_indexes:
                    key = s.literal(*args[index]) if index < len(args) else None
                    if key is not None:
                        reads.append((paths, key, s.rel, s.line(args[index][0])))
        return maps, reads, unresolved

    def run(self):
        for _ in range(100):
            changed = False
            for f in self.functions:
                changed |= self.walk(f, {}, record=False)
            if not changed:
                break
        else:
            raise ScriptError("the cursor paths do not settle")
        maps, reads, unresolved = [], [], []
        for f in self.functions:
            a, b, c = self.walk(f, {}, record=True)
            maps += a; reads += b; unresolved += c
        return maps, reads, unresolved


def normalize(path):
    """('analysis', 'rqd', 'balls', '[]', 'name') -> 'analysis.rqd.balls.name'."""
    return ".".join(p for p in path if p not in ("[]", "*"))


def reader_keys(root):
    sources = [Source(os.path.join(root, rel), rel) for rel in READER_SOURCES]
    header = next(s for s in sources if s.rel == CURSOR_HEADER)
    analysis = Analysis(sources, key_getters(header))
    maps, reads, unresolved = analysis.run()
    if not maps:
        raise ScriptError("no Cursor::map({...}) lists found in the reader")
    accepted = {}       # normalized path -> "file:line"
    by_name_only = {}   # key -> "file:line" (map whose path was not found)
    allowed_at = {}     # normalized map path -> set of keys
    for paths, keys, rel, line in maps:
        where = "%s:%d" % (rel, line)
        if not paths:
            for key in keys:
                by_name_only.setdefault(key, where)
            continue
        for path in paths:
            allowed_at.setdefault(normalize(path), set()).update(keys)
            for key in keys:
                accepted.setdefault(normalize(path + (key,)), where)
    notes = []
    for paths, key, rel, line in reads:
        for path in paths:
            if key not in allowed_at.get(normalize(path), set()):
                notes.append("%s:%d: reads '%s' at '%s', which no allowed-key list there holds "
                             "(the reader would reject it)" % (rel, line, key, normalize(path) or "<top>"))
    for what, line in unresolved:
        notes.append("%s at line %d" % (what, line))
    return accepted, by_name_only, notes


# -------------------------------------------------------------------------------------------
# The page
# -------------------------------------------------------------------------------------------

KEY_PATH = r"[a-z_][a-z0-9_]*(?:\[\])?(?:\.[a-z_][a-z0-9_]*(?:\[\])?)*"


def page_path(text):
    """'balls[].name' -> 'balls.name'."""
    return ".".join(part.replace("[]", "") for part in text.split("."))


def join(*parts):
    return ".".join(p for p in parts if p)


def anchor(heading):
    """GitHub's anchor of a heading."""
    text = heading.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def split_row(line):
    cells = re.split(r"(?<!\\)\|", line.strip())
    if cells and cells[0] == "":
        cells = cells[1:]
    if cells and cells[-1] == "":
        cells = cells[:-1]
    return [c.strip() for c in cells]


def brace_keys(text):
    """Key names of each {a, b} / {a: x, b: y} in text."""
    keys = []
    for group in re.findall(r"\{([^{}]*)\}", text):
        for item in group.split(","):
            name = item.split(":")[0].strip()
            if re.fullmatch(r"[a-z_][a-z0-9_]*", name):
                keys.append(name)
    return keys


def page_keys(root):
    """(documented, mentioned): normalized key paths the page documents (key-table first
    column, section headings, expansions) and those it at least mentions."""
    with open(os.path.join(root, PAGE), encoding="utf-8") as f:
        lines = f.read().split("\n")
    # Sections: heading -> prefix. "Top level" is the root, "Distributions" the keys of a
    # distribution map; any other heading that is not one backticked key path has no prefix.
    sections = []       # dicts: prefix, anchor, rows, prose
    current = None
    in_fence = False
    pending_entry = None
    table = None        # (prefix, header) of the table being read
    for number, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        heading = re.match(r"^(#+)\s+(.*?)\s*$", line)
        if heading:
            title = heading.group(2)
            m = re.fullmatch(r"`(%s)`(?:\s*\(.*\))?" % KEY_PATH, title)
            if m:
                prefix = page_path(m.group(1))
            elif title == "Top level":
                prefix = ""
            elif title == "Distributions":
                prefix = "<distribution>"
            else:
                prefix = None
            current = {"prefix": prefix, "anchor": anchor(title), "rows": [], "prose": [],
                       "title": title}
            sections.append(current)
            pending_entry, table = None, None
            continue
        if current is None:
            continue
        if line.startswith("|"):
            cells = split_row(line)
            if table is None:
                header = [c.lower() for c in cells]
                table = (join(current["prefix"] or "", pending_entry or "")
                         if current["prefix"] not in (None, "<distribution>")
                         else current["prefix"], header)
                pending_entry = None
                if header and header[0] == "key" and current["prefix"] is None:
                    raise ScriptError("%s:%d: a key table under '%s', a heading that names no "
                                      "section" % (PAGE, number, current["title"]))
                continue
            if re.fullmatch(r"[-:| ]+", line):
                continue
            prefix, header = table
            if header[0] != "key":
                continue
            row = dict(zip(header, cells))
            names = re.findall(r"`(%s)`" % KEY_PATH, cells[0])
            if not names:
                raise ScriptError("%s:%d: no backticked key in the first cell" % (PAGE, number))
            for name in names:
                current["rows"].append({"prefix": prefix, "key": page_path(name), "row": row,
                                        "line": number})
            continue
        table = None
        entry = re.match(r"^Each `(%s)` entry:\s*$" % KEY_PATH, line)
        if entry:
            pending_entry = page_path(entry.group(1))
            continue
        current["prose"].append(line)

    distribution_keys = set()
    documented, mentioned = {}, set()
    section_by_anchor = {s["anchor"]: s for s in sections}
    for s in sections:
        if s["prefix"] == "<distribution>":
            distribution_keys.update(r["key"] for r in s["rows"])
    # Explicit rows and section headings.
    for s in sections:
        if s["prefix"] in (None, "<distribution>"):
            continue
        if s["prefix"]:
            documented.setdefault(s["prefix"], "%s heading '%s'" % (PAGE, s["title"]))
        for r in s["rows"]:
            documented.setdefault(join(r["prefix"], r["key"]), "%s:%d" % (PAGE, r["line"]))
    # Expansions: a distribution's keys; the keys of a linked section of the page.
    for s in sections:
        if s["prefix"] in (None, "<distribution>"):
            continue
        for r in s["rows"]:
            path = join(r["prefix"], r["key"])
            where = "%s:%d" % (PAGE, r["line"])
            kind = r["row"].get("type", "")
            if kind.startswith("distribution"):
                for key in distribution_keys:
                    documented.setdefault(join(path, key), where)
            for target in re.findall(r"\]\(#([\w-]+)\)", " ".join(r["row"].values())):
                linked = section_by_anchor.get(target)
                if not linked or linked["prefix"] in (None, "<distribution>"):
                    continue
                base = linked["prefix"]
                for other in list(documented):
                    if other.startswith(base + ".") if base else other:
                        rest = other[len(base) + 1:] if base else other
                        documented.setdefault(join(path, rest), where)
            # Mentions: {a, b} in the type; backticked names in the checks of a map row.
            for key in brace_keys(kind):
                mentioned.add(join(path, key))
            if kind.strip() == "map":
                for key in re.findall(r"`([a-z_][a-z0-9_]*)`", r["row"].get("checks", "")):
                    mentioned.add(join(path, key))
        for key in brace_keys(" ".join(re.findall(r"`([^`]*)`", " ".join(s["prose"])))):
            mentioned.add(join(s["prefix"], key))
    # Every prefix of a documented key is documented.
    for path in list(documented):
        parts = path.split(".")
        for n in range(1, len(parts)):
            documented.setdefault(".".join(parts[:n]), documented[path])
    mentioned |= set(documented)
    for path in list(mentioned):
        parts = path.split(".")
        mentioned.update(".".join(parts[:n]) for n in range(1, len(parts)))
    if not documented:
        raise ScriptError("%s: no key tables found" % PAGE)
    return documented, mentioned


# -------------------------------------------------------------------------------------------

def main(argv):
    if len(argv) != 2:
        print("usage: %s REPO_ROOT" % os.path.basename(argv[0]), file=sys.stderr)
        return 2
    root = argv[1]
    try:
        accepted, by_name_only, notes = reader_keys(root)
        documented, mentioned = page_keys(root)
    except (ScriptError, OSError) as error:
        print("scene_reference_check: cannot check: %s" % error, file=sys.stderr)
        return 2
    mentioned_leaves = {p.split(".")[-1] for p in mentioned}
    missing = sorted((p, w) for p, w in accepted.items()
                     if p not in mentioned and p not in ACCEPTED_NOT_DOCUMENTED_OK)
    missing += sorted(("<path unknown>." + k, w) for k, w in by_name_only.items()
                      if k not in mentioned_leaves)
    unknown_leaves = set(by_name_only)
    extra = sorted((p, w) for p, w in documented.items()
                   if p not in accepted and p.split(".")[-1] not in unknown_leaves
                   and p not in DOCUMENTED_NOT_ACCEPTED_OK)
    for note in notes:
        print("scene_reference_check: note: %s" % note)
    if missing:
        print("scene_reference_check: %d key(s) the reader accepts are not in %s:"
              % (len(missing), PAGE))
        for path, where in missing:
            print("  %-50s (%s)" % (path, where))
    if extra:
        print("scene_reference_check: %d key(s) %s documents are not accepted by the reader:"
              % (len(extra), PAGE))
        for path, where in extra:
            print("  %-50s (%s)" % (path, where))
    if missing or extra:
        return 1
    print("scene_reference_check: OK: %d accepted keys (%d of them by name only) all in %s; "
          "%d documented keys all accepted" % (len(accepted) + len(by_name_only),
                                               len(by_name_only), PAGE, len(documented)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
