"""Property test: mutated bundle files never make the parser raise, and every range is in the file."""

import random

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from plxtools.syntax import ast, parse_text
from tests.conftest import bundle_files, campaign_size

FILES = [p.read_text(encoding="utf-8") for p in bundle_files()[::7]]


def mutate(text: str, ops: list[tuple[int, int, int, str]]) -> str:
    lines = text.split("\n")
    for kind, a, b, chars in ops:
        if not lines:
            break
        i, j = a % len(lines), b % len(lines)
        if kind == 0:
            del lines[i]
        elif kind == 1:
            lines.insert(i, lines[j])
        elif kind == 2:
            lines[i], lines[j] = lines[j], lines[i]
        else:
            line = lines[i]
            k = b % (len(line) + 1)
            lines[i] = line[:k] + chars + line[k:]
    return "\n".join(lines)


def check_ranges(tree):
    n = len(tree.text)
    for d in tree.diagnostics:
        assert 0 <= d.span.start.offset <= d.span.end.offset <= n
    for s in ast.walk_statements(tree.statements):
        assert 0 <= s.span.start.offset <= s.span.end.offset <= n
        assert tree.index.pos(s.header.start.offset) == s.header.start


@settings(max_examples=campaign_size(150), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.integers(0, len(FILES) - 1),
    st.lists(
        st.tuples(st.integers(0, 3), st.integers(0, 10_000), st.integers(0, 10_000),
                  st.text(alphabet=' :.,()[]{}"#`@$-+*/=\t\nabcxyz019', max_size=4)),
        min_size=1, max_size=6,
    ),
)
def test_mutated_bundle_files_never_raise(index, ops):
    text = mutate(FILES[index], ops)
    tree = parse_text(text)
    check_ranges(tree)


@settings(max_examples=campaign_size(100), deadline=None)
@given(st.text(max_size=300))
def test_arbitrary_text_never_raises(text):
    check_ranges(parse_text(text))


def test_seeded_random_corpus():
    rng = random.Random(1234)
    for text in FILES:
        ops = [(rng.randrange(4), rng.randrange(10_000), rng.randrange(10_000), rng.choice(['"', ":", "[", "#", "\t"]))
               for _ in range(3)]
        check_ranges(parse_text(mutate(text, ops)))
