"""Case files (case.yaml, docs/case-file.md) written from a Python dict, with the comments that
say why a value is what it is, and read back.

    from cocopp import case

    text = case.dump({
        "settings": {"delta_t": 1.0e-4, "number_of_timesteps": case.commented(100, "10 ms")},
        "coupled_solver": {"type": "iqni", "predictor": case.flow({"type": "linear"})},
        "solver_wrappers": [{"type": "tube_flow", "name": "flow"}]},
        header="The tube, written by make_tube.py")

A dict is written one key a line, a list of dicts one item after the other (`- key: ...`), a
list of plain values and a dict wrapped in `flow` on one line (`[flag]`, `{type: linear}`);
`commented(value, text)` puts `# text` after the value's line, and a text of several lines goes
on in comment lines below it; an item of a list with a comment puts the list one item a line.
Values are written by yaml, and dump checks that its text loads back as the same dict.
"""
import pathlib

LINE_WIDTH_UNLIMITED = 1 << 30  # a value yaml writes on one line, however long
COMMENT_COLUMN = 34  # where comments start, unless the line is longer
INDENT = "  "


class Commented:
    """A value with the comment written after it."""

    def __init__(self, value, comment):
        self.value, self.comment = value, comment


class Flow:
    """A dict written on one line: {type: linear}."""

    def __init__(self, mapping):
        self.mapping = dict(mapping)


def commented(value, comment):
    return Commented(value, comment)


def flow(mapping):
    return Flow(mapping)


def plain(value):
    """`value` without its comments and flow marks: what yaml reads back from dump's text."""
    if isinstance(value, Commented):
        return plain(value.value)
    if isinstance(value, Flow):
        return plain(value.mapping)
    if isinstance(value, dict):
        return {key: plain(item) for key, item in value.items()}
    if isinstance(value, list):
        return [plain(item) for item in value]
    return value


def dump(case, header=None):
    """The case file's text: `header` (lines of text) as comments, then the case."""
    import yaml

    lines = [f"# {line}".rstrip() for line in header.splitlines()] if header else []
    for text, comment in _mapping_lines(case, 0):
        lines.extend(_with_comment(text, comment))
    text = "\n".join(lines) + "\n"
    if yaml.load(text, Loader=_fast(yaml, "SafeLoader")) != plain(case):
        raise ValueError("case.dump: the text does not load back as the case:\n" + text)
    return text


def write(path, case, header=None):
    pathlib.Path(path).write_text(dump(case, header))


def read(path):
    """A case file (or any YAML file) as a dict."""
    import yaml

    return yaml.load(pathlib.Path(path).read_text(), Loader=_fast(yaml, "SafeLoader"))


def _fast(yaml, name):
    """libyaml's SafeLoader or SafeDumper where python3-yaml has it (Debian's does), else
    PyYAML's own: libyaml is ten times faster on long cases (bench/case_check_scaling.py)."""
    return getattr(yaml, "C" + name, getattr(yaml, name))


def _unwrap(value):
    return (value.value, value.comment) if isinstance(value, Commented) else (value, None)


def _is_block_mapping(value):
    return isinstance(value, dict) and len(value) > 0


def _is_block_list(value):
    """A list written one item a line: of dicts, or with a comment on an item."""
    return isinstance(value, list) and any(
        isinstance(item, (dict, Flow, list, Commented)) for item in value)


def _mapping_lines(mapping, depth):
    """[(line, comment)] of a dict written one key a line at `depth`."""
    lines = []
    pad = INDENT * depth
    for key, item in mapping.items():
        value, comment = _unwrap(item)
        if _is_block_mapping(value):
            lines.append((f"{pad}{key}:", comment))
            lines += _mapping_lines(value, depth + 1)
        elif _is_block_list(value):
            lines.append((f"{pad}{key}:", comment))
            for element in value:
                lines += _list_item_lines(element, depth + 1)
        else:
            lines.append((f"{pad}{key}: {_inline(value)}", comment))
    return lines


def _list_item_lines(item, depth):
    """[(line, comment)] of one item of a list of dicts: `- ` before its first line."""
    value, comment = _unwrap(item)
    pad = INDENT * depth
    if not _is_block_mapping(value):
        return [(f"{pad}- {_inline(value)}", comment)]
    lines = _mapping_lines(value, depth + 1)
    first, first_comment = lines[0]
    if comment and first_comment:
        raise ValueError(f"case.dump: two comments for one line: {comment!r}, {first_comment!r}")
    lines[0] = (f"{pad}- {first.lstrip()}", comment or first_comment)
    return lines


def _inline(value):
    """A value on one line, as yaml writes it: a number, a string (quoted where needed), a
    list in brackets or a dict in braces."""
    import yaml

    text = yaml.dump(plain(value), Dumper=_fast(yaml, "SafeDumper"), default_flow_style=True,
                     width=LINE_WIDTH_UNLIMITED, sort_keys=False)
    return text.removesuffix("\n").removesuffix("\n...")


def _with_comment(text, comment):
    if not comment:
        return [text]
    first, *more = comment.splitlines()
    return ([f"{text:<{max(COMMENT_COLUMN, len(text) + 2)}}# {first}"]
            + [f"{'':<{COMMENT_COLUMN}}# {line}" for line in more])
