"""The full analysis never raises on broken or half-typed files (the language server runs it per keystroke)."""

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from plxtools.config import Config
from plxtools.rules.analysis import analyse_tree
from plxtools.syntax import parse_text
from tests.conftest import REPO, bundle_files, campaign_size
from tests.syntax.test_mutation import mutate

SOURCES = [p.read_text(encoding="utf-8") for p in bundle_files()[::11]]
SOURCES.append((REPO / "examples" / "boxtruck" / "boxtruck.openplx").read_text())

_WS = None


def ws():
    global _WS
    if _WS is None:
        from plxtools.model.workspace import Workspace

        _WS = Workspace()
    return _WS


@settings(max_examples=campaign_size(120), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.integers(0, len(SOURCES) - 1),
    st.lists(st.tuples(st.integers(0, 3), st.integers(0, 10_000), st.integers(0, 10_000),
                       st.sampled_from([":", " is ", ".", "(", "{", "x", " becomes Real", "this", "[", "1", "\n    "])),
             min_size=1, max_size=5),
)
def test_analysis_of_mutated_sources_never_raises(index, ops):
    text = mutate(SOURCES[index], ops)
    tree = parse_text(text, "/tmp/robust/mutated.openplx")
    diags = analyse_tree(tree, Config(), ws())
    for d in diags:
        assert 0 <= d.span.start.offset <= d.span.end.offset <= len(text)


def test_every_prefix_of_the_example_analyses():
    """Typing the BoxTruck from top to bottom: every intermediate text is analysable."""
    text = SOURCES[-1]
    for cut in range(0, len(text), 37):
        analyse_tree(parse_text(text[:cut], "/tmp/robust/typing.openplx"), Config(), ws())
