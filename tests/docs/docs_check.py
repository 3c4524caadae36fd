"""Checks that the project's documentation is self-contained.

* Every relative Markdown link in README.md, docs/*.md and configs/**/README.md (and every other
  Markdown file of the repository) resolves: the file exists, and a `#anchor` names a heading of
  the target file (GitHub's slug of the heading text).
* Every plain-text pointer `docs/<name>.md#<anchor>` in any text file of the repository (code
  comments, YAML, READMEs) resolves the same way; further `#anchor`s later on the same line refer
  to the same file ("docs/environments.md#agents, #ball").
* No file refers to the shared folder outside the repository, and no file outside docs/ cites
  sections of an external specification ("spec" followed by a section sign).

Run as a script it prints every problem and exits 1 if there is any.
"""

import os
import re
import sys
import unicodedata

SKIP_DIRS = {'.git', '__pycache__', 'runs', 'sweeps', 'node_modules'}  # and build*
MAX_BYTES = 4 * 1024 * 1024

# Spelled in pieces so that this file does not trip its own checks.
FORBIDDEN_OUTSIDE_REFERENCES = ('../' + 'shared', 'shared/' + 'spec', 'shared/' + 'golden',
                                'shared/' + 'reference')
SPEC_CITATION = re.compile('spec' + r'\s*\u00a7', re.IGNORECASE)

MD_LINK = re.compile(r'(?<!!)\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
MD_IMAGE = re.compile(r'!\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
DOCS_POINTER = re.compile(r'(?<![\w/.])docs/([\w-]+\.md)#([\w-]+)')
FURTHER_ANCHOR = re.compile(r'(?:^|[\s(,])#([a-z0-9][\w-]*)')
FENCE = re.compile(r'^\s*(```|~~~)')
HEADING = re.compile(r'^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$')
HTML_ANCHOR = re.compile(r'<a\s+(?:name|id)\s*=\s*"([^"]+)"', re.IGNORECASE)


def github_slug(heading_text):
    """GitHub's anchor for a heading: the rendered text, lower-cased, with everything but
    letters, digits, spaces, hyphens and underscores removed and spaces turned into hyphens."""
    text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', heading_text)  # [text](url) -> text
    text = re.sub(r'<[^>]+>', '', text)  # inline HTML tags
    text = text.strip().lower()
    kept = []
    for ch in text:
        if ch in (' ', '-', '_') or ch.isalnum() or unicodedata.category(ch) in ('Mn', 'Pc'):
            kept.append(ch)
    return ''.join(kept).replace(' ', '-')


def anchors_of(markdown_text):
    """The anchors GitHub makes for a Markdown file (duplicates get -1, -2, ...)."""
    anchors = set()
    seen = {}
    in_fence = False
    for line in markdown_text.splitlines():
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        for name in HTML_ANCHOR.findall(line):
            anchors.add(name)
        match = HEADING.match(line)
        if not match:
            continue
        slug = github_slug(match.group(2))
        count = seen.get(slug, 0)
        seen[slug] = count + 1
        anchors.add(slug if count == 0 else f'{slug}-{count}')
    return anchors


def _strip_code(markdown_line):
    """A Markdown line without its inline code spans (links inside them are not links)."""
    return re.sub(r'`[^`]*`', '', markdown_line)


class Checker:
    def __init__(self, root):
        self.root = os.path.abspath(root)
        self._anchor_cache = {}
        self.problems = []

    def _anchors(self, path):
        if path not in self._anchor_cache:
            with open(path, encoding='utf-8') as f:
                self._anchor_cache[path] = anchors_of(f.read())
        return self._anchor_cache[path]

    def _report(self, path, line_number, message):
        relative = os.path.relpath(path, self.root)
        self.problems.append(f'{relative}:{line_number}: {message}')

    def _check_target(self, source, line_number, target_path, anchor, shown):
        if not os.path.exists(target_path):
            self._report(source, line_number, f'{shown}: no such file')
            return
        if anchor is None:
            return
        if os.path.isdir(target_path) or not target_path.endswith('.md'):
            self._report(source, line_number, f'{shown}: anchor on a file that is not Markdown')
            return
        if anchor not in self._anchors(target_path):
            self._report(source, line_number, f'{shown}: no heading with anchor #{anchor}')

    def text_files(self):
        for directory, subdirs, files in os.walk(self.root):
            subdirs[:] = sorted(d for d in subdirs
                                if d not in SKIP_DIRS and not d.startswith('build'))
            for name in sorted(files):
                path = os.path.join(directory, name)
                try:
                    if os.path.getsize(path) > MAX_BYTES:
                        continue
                    with open(path, encoding='utf-8') as f:
                        yield path, f.read()
                except (UnicodeDecodeError, OSError):
                    continue  # binary or unreadable: not documentation

    def check_markdown_links(self, path, text):
        in_fence = False
        for number, line in enumerate(text.splitlines(), 1):
            if FENCE.match(line):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            stripped = _strip_code(line)
            for target in MD_LINK.findall(stripped) + MD_IMAGE.findall(stripped):
                if re.match(r'^[a-z][a-z0-9+.-]*:', target, re.IGNORECASE):
                    continue  # http:, https:, mailto: ...: not ours to check
                file_part, _, anchor = target.partition('#')
                if file_part == '':
                    target_path = path
                elif file_part.startswith('/'):
                    target_path = os.path.join(self.root, file_part.lstrip('/'))
                else:
                    target_path = os.path.normpath(os.path.join(os.path.dirname(path), file_part))
                self._check_target(path, number, target_path, anchor or None, f'link {target}')

    def check_docs_pointers(self, path, text):
        is_markdown = path.endswith('.md')
        for number, line in enumerate(text.splitlines(), 1):
            if is_markdown:
                line = re.sub(r'\]\([^)]*\)', '](...)', line)  # link targets: checked as links
            pointers = list(DOCS_POINTER.finditer(line))
            for index, match in enumerate(pointers):
                target_path = os.path.join(self.root, 'docs', match.group(1))
                shown = f'docs/{match.group(1)}#{match.group(2)}'
                self._check_target(path, number, target_path, match.group(2), shown)
                end = pointers[index + 1].start() if index + 1 < len(pointers) else len(line)
                for further in FURTHER_ANCHOR.finditer(line[match.end():end]):
                    self._check_target(path, number, target_path, further.group(1),
                                       f'docs/{match.group(1)}#{further.group(1)}')

    def check_self_contained(self, path, text):
        relative = os.path.relpath(path, self.root)
        in_docs = relative.split(os.sep)[0] == 'docs'
        for number, line in enumerate(text.splitlines(), 1):
            for forbidden in FORBIDDEN_OUTSIDE_REFERENCES:
                if forbidden in line:
                    self._report(path, number, f'refers outside the repository ({forbidden})')
            if not in_docs and SPEC_CITATION.search(line):
                self._report(path, number, 'cites an external specification; point at docs/')

    def run(self):
        for path, text in self.text_files():
            if path.endswith('.md'):
                self.check_markdown_links(path, text)
            self.check_docs_pointers(path, text)
            self.check_self_contained(path, text)
        return self.problems


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), '..', '..')
    problems = Checker(root).run()
    for problem in problems:
        print(problem)
    print(f'{len(problems)} problem(s)')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
