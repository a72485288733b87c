#!/usr/bin/env python3
"""Fails when one fully qualified type name is defined in more than one file.

usage: check_type_names.py DIR... -> prints each clash as `name: file, file`; exit 1 if any

Two definitions of `simtree::reconstruction::Skeleton` in two headers break the one-definition rule
once both are linked into one program, whether or not they differ today. This check reads the
sources (C++ comments and literals stripped, braces tracked) and records every class, struct, union
and enum defined at namespace scope under its namespace path. Types in anonymous namespaces and in
function or class bodies are local to their file and are skipped; a type defined twice in one file
(alternative #if branches) is not a clash. The LTO link with -Wodr (`make odr-check`) is the
compiler's version of the same guard; this one runs in a second, so every `make test` runs it.
"""
import os
import re
import sys

SOURCE_SUFFIXES = ('.h', '.hpp', '.cc', '.cpp')
TOKEN = re.compile(r'[A-Za-z_]\w*(?:\s*::\s*[A-Za-z_]\w*)*|[{};<>()=]')


def strip_comments_and_literals(text):
    """Blanks out comments, string and character literals and preprocessor lines."""
    out, i, n = [], 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == '#':
            end = i
            while end < n and (text[end] != '\n' or text[end - 1] == '\\'):
                end += 1
            i = end
            continue
        if c == '/' and text.startswith('//', i):
            i = text.find('\n', i)
            i = n if i < 0 else i
            continue
        if c == '/' and text.startswith('/*', i):
            end = text.find('*/', i + 2)
            i = n if end < 0 else end + 2
            out.append(' ')
            continue
        if c == 'R' and text.startswith('R"', i):
            delimiter = text[i + 2:text.find('(', i + 2)]
            end = text.find(')' + delimiter + '"', i)
            i = n if end < 0 else end + len(delimiter) + 2
            out.append('""')
            continue
        if c in '"\'':
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == '\\' else 1
            i = j + 1
            out.append('""')
            continue
        if c == '\n':
            at_line_start = True
        elif not c.isspace():
            at_line_start = False
        out.append(c)
        i += 1
    return ''.join(out)


def defined_types(text):
    """Yields the qualified names of the types defined at namespace scope in one source."""
    scopes = []  # one entry per open brace: a namespace name, '' (anonymous) or None (a body)
    statement = []  # tokens since the last ';', '{' or '}'
    for token in TOKEN.findall(strip_comments_and_literals(text)):
        if token == '{':
            at_namespace_scope = all(scope for scope in scopes)
            if statement[:1] == ['namespace']:
                scopes.append(statement[1].replace(' ', '') if len(statement) > 1 else '')
            else:
                head = _type_head(statement) if at_namespace_scope else None
                if head:
                    yield '::'.join(scopes + [head])
                scopes.append(None)
            statement = []
        elif token == '}':
            if scopes:
                scopes.pop()
            statement = []
        elif token == ';':
            statement = []
        else:
            statement.append(token)


def _type_head(statement):
    """The name a statement defines as a type, once its `{` is next, else None."""
    keywords = ('class', 'struct', 'union', 'enum')
    depth = 0
    for index, token in enumerate(statement):
        if token == '<':
            depth += 1
        elif token == '>':
            depth -= 1
        elif depth == 0 and token in keywords:
            rest = statement[index + 1:]
            if rest and rest[0] in ('class', 'struct'):  # enum class
                rest = rest[1:]
            if not rest or not re.match(r'[A-Za-z_]', rest[0]) or rest[0] in ('final',):
                return None
            if len(rest) > 1 and rest[1] == '<':
                return None  # a specialisation: its primary template carries the name
            if any(t in ('(', ')', '=') for t in rest):
                return None  # a function returning or a variable of an elaborated type
            return rest[0].replace(' ', '')
    return None


def main(roots):
    definitions = {}
    for root in roots:
        for directory, _, files in os.walk(root):
            for name in sorted(files):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.join(directory, name)
                with open(path, encoding='utf-8', errors='replace') as source:
                    for qualified in set(defined_types(source.read())):
                        definitions.setdefault(qualified, set()).add(path)
    clashes = {name: files for name, files in definitions.items() if len(files) > 1}
    for name, files in sorted(clashes.items()):
        print(f"{name}: {', '.join(sorted(files))}")
    return 1 if clashes else 0


if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1:]))
