"""Property tests: generated programs and scrambled bundle files format stably and keep their
meaning, judged by the tests' own checks rather than the formatter's safety net."""

from __future__ import annotations

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from plxtools.fmt import format_text
from plxtools.syntax import parse_text
from tests.conftest import bundle_files, campaign_size
from tests.fmt.helpers import assert_fixed_point, assert_same_lint, assert_same_meaning, assert_same_tokens
from tests.fmt.programs import mutate, programs

SETTINGS = settings(
    max_examples=campaign_size(120),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
BUNDLE_TEXTS = [p.read_text(encoding="utf-8-sig") for p in bundle_files()]


def _check(source: str) -> None:
    assume(not parse_text(source).has_errors)
    result = format_text(source)
    assert result.ok, result.internal_error
    assert_same_meaning(source, result.text)
    assert_same_tokens(source, result.text)
    assert_same_lint(source, result.text)
    assert_fixed_point(result.text)


@SETTINGS
@given(programs())
def test_generated_programs_format_stably_and_keep_their_meaning(source):
    _check(source)


@SETTINGS
@given(st.sampled_from(BUNDLE_TEXTS), st.randoms(use_true_random=False))
def test_scrambled_bundle_files_format_stably_and_keep_their_meaning(text, rnd):
    _check(mutate(text, rnd))


@SETTINGS
@given(st.sampled_from(BUNDLE_TEXTS), st.randoms(use_true_random=False))
def test_output_does_not_depend_on_spacing_or_indentation_width(text, rnd):
    """Changing only spaces between tokens and the indentation width changes nothing in the output."""
    scrambled = mutate(text, rnd, extras=False)
    assert format_text(scrambled).text == format_text(text).text
