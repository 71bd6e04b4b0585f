"""Random OpenPLX programs for property tests: a small generator of valid files in messy layouts,
and a mutator that scrambles the layout of real bundle files without touching their meaning."""

from __future__ import annotations

import random

from hypothesis import strategies as st

from plxtools.syntax.lexer import lex

IDENTS = ["a", "b", "mass", "x_1", "radius", "Foo", "Vec3", "`dotted.name`", "e00", "in", "type"]
TYPES = ["Real", "Int", "Bool", "Math.Vec3", "Physics3D.Bodies.RigidBody", "Base"]
NUMBERS = ["0", "1", "2.5", "1e8", "5.0e-3", "9.80665", "45400000"]
STRINGS = ['"text"', '"# not a comment"', '@"mesh.obj"', '$"{DIR}/x.png"', '""']
COMMENTS = ["# note", "#tight", "# plx: ignore[C001]", "#   spaced   ", "# with ] [ ( brackets"]
DIRECTIVES = ["# plx: fmt: off", "# plx: fmt: on"]


class Maker:
    """Builds one program with a `random.Random`; the layout is as messy as real files get."""

    def __init__(self, rnd: random.Random):
        self.r = rnd
        self.out: list[str] = []

    # ------------------------------------------------------------- expressions as token lists
    def expr(self, depth: int = 0) -> list[str]:
        r = self.r
        if depth > 3 or r.random() < 0.35:
            kind = r.choice(["num", "name", "dotted", "str", "kw"])
            if kind == "num":
                return [r.choice(NUMBERS)]
            if kind == "name":
                return [r.choice(IDENTS)]
            if kind == "dotted":
                return [r.choice(IDENTS), ".", r.choice(IDENTS)]
            if kind == "str":
                return [r.choice(STRINGS)]
            return [r.choice(["true", "false", "this"])]
        kind = r.choice(["neg", "bin", "paren", "call", "index", "brace", "array", "member"])
        if kind == "neg":
            return ["-"] + self.expr(depth + 1)
        if kind == "bin":
            return self.expr(depth + 1) + [r.choice("+-*/")] + self.expr(depth + 1)
        if kind == "paren":
            return ["("] + self.expr(depth + 1) + [")"]
        if kind == "call":
            return [r.choice(IDENTS), "("] + self.args(depth) + [")"]
        if kind == "index":
            return [r.choice(IDENTS), "[", r.choice(["0", "1", "12"]), "]"]
        if kind == "member":
            return [r.choice(IDENTS), "(", ")", ".", r.choice(IDENTS)]
        opener, closer = ("{", "}") if kind == "brace" else ("[", "]")
        return [opener] + self.args(depth) + [closer]

    def args(self, depth: int) -> list[str]:
        n = self.r.choice([0, 1, 2, 3, 5])
        toks: list[str] = []
        for i in range(n):
            if i:
                toks.append(",")
            toks += self.expr(depth + 1)
        if n and self.r.random() < 0.15:
            toks.append(",")  # trailing comma
        return toks

    # ------------------------------------------------------------- joining tokens with messy spacing
    def join(self, toks: list[str], indent: int) -> str:
        r = self.r
        parts: list[str] = []
        depth = 0
        for i, t in enumerate(toks):
            if i:
                prev = toks[i - 1]
                wordy = prev[-1].isalnum() or prev[-1] in '_`"' or prev in ")]}"
                need = wordy and (t[0].isalnum() or t[0] in '_`"@$')
                if depth > 0 and r.random() < 0.25:
                    pad = " " * (indent + r.randint(1, 10))
                    parts.append(
                        r.choice(
                            [
                                "\n" + pad,
                                "  " + r.choice(COMMENTS) + "\n" + pad,
                                "\n" + pad + r.choice(COMMENTS) + "\n" + pad,
                            ]
                        )
                    )
                else:
                    parts.append(" " * (r.choice([0, 0, 1, 1, 2]) or int(need)))
            parts.append(t)
            if t in "([{":
                depth += 1
            elif t in ")]}":
                depth -= 1
        return "".join(parts)

    # ------------------------------------------------------------- statements
    def line(self, indent: int, text: str, tab: bool = False) -> None:
        lead = "\t" * (indent // 4) + " " * (indent % 4) if tab else " " * indent
        trail = ""
        if self.r.random() < 0.2:
            trail = " " * self.r.randint(0, 3) + self.r.choice(COMMENTS)
        elif self.r.random() < 0.1:
            trail = " " * self.r.randint(1, 3)  # trailing whitespace
        self.out.append(lead + text + trail)

    def gap(self, indent: int) -> None:
        r = self.r
        for _ in range(r.choice([0, 0, 0, 1, 1, 2, 3])):
            self.out.append(" " * r.randint(0, 6))
        if r.random() < 0.15:
            text = r.choice(COMMENTS + DIRECTIVES) if r.random() < 0.3 else r.choice(COMMENTS)
            self.out.append(" " * max(0, indent + r.randint(-4, 6)) + text)

    def triple(self) -> str:
        r = self.r
        lines = [
            r.choice(["", "Doc text.", "  indented   ", "x: 1", "    # not a comment"]) for _ in range(r.randint(0, 3))
        ]
        return '"""' + r.choice(["", "First line"]) + ("\n" + "\n".join(lines) + "\n" if lines else "") + '"""'

    def member(self, indent: int, depth: int, tab: bool) -> None:
        r = self.r
        name, typ = r.choice(IDENTS), r.choice(TYPES)
        kind = r.choice(
            ["decl", "decl_val", "assign", "becomes", "with", "doc", "fn", "block", "block", "opt", "ref", "array"]
        )
        if kind == "block" and depth < 4:
            head = r.choice(
                [
                    f"{name} is {typ}:",
                    f"{name}.{r.choice(IDENTS)}:",
                    f"{name} becomes {typ}:",
                    f"{name} is {typ} with Tr, Other:",
                ]
            )
            self.line(indent, head, tab)
            self.block(indent, depth + 1, tab)
            return
        texts = {
            "decl": f"{name}   is {typ}",
            "decl_val": f"{name} is {typ}:" + self.join(self.expr(), indent),
            "assign": f"{name}.{r.choice(IDENTS)} :" + " " + self.join(self.expr(), indent),
            "becomes": f"{name} becomes {typ} reference",
            "with": "with " + ", ".join(r.sample(["A", "B.C", "Tr"], r.randint(1, 3))),
            "doc": ".doc: " + (self.triple() if r.random() < 0.5 else '"short doc"'),
            "fn": r.choice(["fn length( ) -> Real", "static fn from_xyz(x : Real,y: Real) -> Vec3", "fn on_init()"]),
            "opt": f"optional {name} is {typ}",
            "ref": f"optional {name} is {typ} reference",
            "array": f"{name} is {typ}[]: " + self.join(["["] + self.args(1) + ["]"], indent),
            "block": f"{name}: 1",
        }
        self.line(indent, texts[kind], tab)

    def block(self, header_indent: int, depth: int, tab: bool) -> None:
        r = self.r
        indent = header_indent + r.choice([1, 2, 2, 3, 4, 4, 4, 5, 8, 9])
        for i in range(r.randint(1, 4)):
            if i:
                self.gap(indent)
            before = len(self.out)
            self.member(indent, depth, tab)
            opened = len(self.out) > before + 1  # a block header and its lines
            if not opened and i and r.random() < 0.1:
                # a sibling written further right than the first one (the parser accepts it)
                self.out[before] = " " * r.randint(1, 3) + self.out[before]

    def program(self) -> str:
        r = self.r
        tab = r.random() < 0.1
        for i in range(r.randint(0, 4)):
            self.gap(0)
            kind = r.choice(["model", "model", "bare", "const", "trait", "operator", "global", "import"])
            name = r.choice(["Wheel", "Chassis", "Scene", "Thing"])
            if kind == "bare":
                self.line(0, f"{name}  is {r.choice(TYPES)}")
            elif kind == "operator":
                self.line(0, r.choice(["operator +(a: T, b: T) -> T", "operator - (a : T)->T"]))
            elif kind == "global":
                self.line(0, "GRAVITY is Real: " + self.join(self.expr(), 0))
            elif kind == "import":
                self.line(0, 'import @"mesh.obj" as Mesh')
            else:
                head = {
                    "model": f"{name} is {r.choice(TYPES)}:",
                    "const": f"const {name}:",
                    "trait": f"trait {name}T is Other:",
                }[kind]
                self.line(0, head)
                self.block(0, 1, tab)
        newline = "\r\n" if r.random() < 0.15 else "\n"
        text = newline.join(self.out)
        return text + (newline if r.random() < 0.8 else "")


@st.composite
def programs(draw) -> str:
    return Maker(draw(st.randoms(use_true_random=False))).program()


def mutate(text: str, rnd: random.Random, extras: bool = True) -> str:
    """Scramble the layout of a valid file: spacing between tokens and indentation width, and
    with `extras` also line breaks inside brackets, comments and blank lines. Lines inside
    \"\"\" strings are left alone."""
    lexed = lex(text)
    parts: list[str] = []
    pos = 0
    for ln in lexed.lines:
        depth = 0
        for k, t in enumerate(ln.tokens):
            between = text[pos : t.start_pos]
            if k and "\n" not in between and "#" not in between:
                if extras and depth > 0 and rnd.random() < 0.1:
                    between = "\n" + " " * (ln.indent + rnd.randint(1, 8))
                elif rnd.random() < 0.3:
                    between = " " * rnd.randint(1 if between else 0, 3)
            parts.append(between)
            parts.append(text[t.start_pos : t.end_pos])
            pos = t.end_pos
            if t.type in ("LPAR", "LSQB", "LBRACE"):
                depth += 1
            elif t.type in ("RPAR", "RSQB", "RBRACE"):
                depth -= 1
        if (
            extras
            and rnd.random() < 0.1
            and "#" not in text[pos : text.find("\n", pos) if "\n" in text[pos:] else len(text)]
        ):
            parts.append("  " + rnd.choice(COMMENTS))
    parts.append(text[pos:])
    scrambled = "".join(parts)

    return _reindent(scrambled, rnd, extras)


def _reindent(text: str, rnd: random.Random, extras: bool) -> str:
    """Scale every indentation by one factor (order is kept, so the meaning is) and sprinkle
    comment and blank lines, never inside a string."""
    strings = [(t.start_pos, t.end_pos) for ln in lex(text).lines for t in ln.tokens if t.type == "STRING"]
    widths = [len(raw) - len(raw.lstrip(" ")) for raw in text.split("\n")]
    factor = rnd.choice([1.0, 2.0, 3.0] + ([0.5] if all(w % 2 == 0 for w in widths) else []))
    out: list[str] = []
    offset = 0
    for raw in text.split("\n"):
        inside = any(s < offset < e for s, e in strings)
        body = raw.lstrip(" ")
        if not inside:
            if body:
                raw = " " * int((len(raw) - len(body)) * factor) + body
            if extras and rnd.random() < 0.04:
                out.append(" " * rnd.randint(0, 8) + rnd.choice(COMMENTS))
            if extras and rnd.random() < 0.04:
                out.append(" " * rnd.randint(0, 4))
        out.append(raw)
        offset = _next_offset(text, offset)
    return "\n".join(out)


def _next_offset(text: str, offset: int) -> int:
    nl = text.find("\n", offset)
    return len(text) + 1 if nl < 0 else nl + 1
