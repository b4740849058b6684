"""Editing of Signorini parameter files: the entries a script or a test
sets in a derived file, so that each entry is set once (the program
refuses a second 'set' of the same entry)."""
import os
import re
import sys


class Section:
    """A subsection: its name, its header and 'end' lines, and its items
    (text lines and subsections, in order)."""

    def __init__(self, name, header=None):
        self.name, self.header, self.items, self.end = name, header, [], None


def parse(lines):
    top = Section("")
    stack = [top]
    for line in lines:
        text = line.split("#", 1)[0].strip()
        m = re.match(r"subsection\s+(.*)$", text)
        if m:
            section = Section(m.group(1).strip(), line)
            stack[-1].items.append(section)
            stack.append(section)
        elif text == "end" and len(stack) > 1:
            stack[-1].end = line
            stack.pop()
        else:
            stack[-1].items.append(line)
    return top


def write(section, out, depth=0):
    for item in section.items:
        if isinstance(item, Section):
            out.append(item.header)
            write(item, out, depth + 1)
            out.append(item.end if item.end is not None else "  " * depth + "end")
        else:
            out.append(item)
    return out


def matches(pattern, name):
    return re.fullmatch(re.escape(pattern).replace(r"\*", r"\d+"), name) is not None


def assign(section, parts, value, depth=0):
    """Sets parts[-1] = value below @section along parts[:-1]; True if some
    subsection matched (a '*' part matches existing numbered ones only)."""
    if len(parts) == 1:
        entry = parts[0]
        line = "  " * depth + "set " + entry + " = " + value
        for i, item in enumerate(section.items):
            if isinstance(item, str):
                m = re.match(r"\s*set\s+(.*?)\s*=", item.split("#", 1)[0])
                if m and m.group(1) == entry:
                    section.items[i] = line
                    return True
        section.items.append(line)
        return True
    head = parts[0]
    found = False
    for item in section.items:
        if isinstance(item, Section) and matches(head, item.name):
            found |= assign(item, parts[1:], value, depth + 1)
    if not found and "*" not in head:
        new = Section(head, "  " * depth + "subsection " + head)
        new.end = "  " * depth + "end"
        section.items.append(new)
        found = assign(new, parts[1:], value, depth + 1)
    return found


def edit_prm(lines, assignments):
    """The lines of a parameter file with each 'path=value' of
    @assignments set: an existing 'set' line at the path is replaced, a
    missing one is added to its subsection (created where the path has no
    '*')."""
    top = parse(lines)
    for assignment in assignments:
        path, value = assignment.split("=", 1)
        parts = [p.strip() for p in path.split("/")]
        if not assign(top, parts, value.strip()):
            sys.exit("prm_edit: no subsection matches " + path)
    return write(top, [])


def absolute_paths(lines, directory):
    """Relative 'include' and 'Mesh file' paths made absolute: the program
    takes them from the directory of the file, and the derived files are
    written elsewhere."""
    out = []
    for line in lines:
        m = re.match(r"(\s*include\s+)(\S+)(.*)$", line)
        if m and not os.path.isabs(m.group(2)):
            line = m.group(1) + os.path.join(directory, m.group(2)) + m.group(3)
        m = re.match(r"(\s*set\s+Mesh file\s*=\s*)(\S+)(.*)$", line)
        if m and not os.path.isabs(m.group(2)):
            line = m.group(1) + os.path.join(directory, m.group(2)) + m.group(3)
        out.append(line)
    return out


def remove_section(lines, path):
    """The lines without the subsection at @path ('A/B': subsection B of
    the top-level subsection A; all its blocks)."""
    top = parse(lines)
    parts = [p.strip() for p in path.split("/")]

    def remove(section, parts):
        if len(parts) == 1:
            section.items = [i for i in section.items
                             if not (isinstance(i, Section) and i.name == parts[0])]
            return
        for item in section.items:
            if isinstance(item, Section) and item.name == parts[0]:
                remove(item, parts[1:])

    remove(top, parts)
    return write(top, [])
