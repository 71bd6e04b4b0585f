"""The editor reads half-typed text with the real lexer (plxtools/syntax/fragments.py)."""

from plxtools.syntax.fragments import dotted_name, ends_in_comment_or_string, fragment_tokens, matching_close


def test_comment_and_open_string_at_the_cursor():
    assert ends_in_comment_or_string('x: 1 # note')
    assert ends_in_comment_or_string('x: "open')
    assert ends_in_comment_or_string('x: """open')
    assert not ends_in_comment_or_string('x: "a # not a comment" ')
    assert not ends_in_comment_or_string('x: "closed"')
    assert not ends_in_comment_or_string("    y is Foo.")


def test_chain_tokens_brackets_and_backticked_names():
    toks = fragment_tokens("a.`b c`(x, y[1]).d[0]")
    assert dotted_name(toks, 0) == (["a", "b c"], 3)
    close = matching_close(toks, 3)
    assert str(toks[close]) == ")" and str(toks[close + 2]) == "d"
    assert matching_close(fragment_tokens("f(a, [b"), 1) == -1
