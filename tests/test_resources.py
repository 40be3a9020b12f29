"""Templates: HTML ones escape what they print (as html.escape does), LaTeX and source templates print it as it is."""

from __future__ import annotations

import html

import jinja2
import markupsafe

from symjac.resources import HTML_SUFFIX, environment, render_template

NASTY = "<b>Craig's \"arm\" & co</b>"


def test_html_templates_escape_every_value_like_html_escape_and_keep_safe_markup():
    template = environment(True).from_string("<p>{{ text }}</p>{{ body | safe }}")
    assert template.render(text=NASTY, body="<i>x</i>") == f"<p>{html.escape(NASTY)}</p><i>x</i>"
    assert template.render(text=markupsafe.Markup("<i>y</i>"), body="") == "<p><i>y</i></p>"


def test_other_templates_print_values_as_they_are():
    assert environment(False).from_string("{{ text }}").render(text=NASTY) == NASTY


def test_the_report_is_the_html_template_and_escapes_user_strings():
    page = render_template(f"documents/report{HTML_SUFFIX}", version="1", robot=NASTY, source="a&b.toml",
                           description=NASTY, sections=[])
    assert NASTY not in page and f"<title>{html.escape(NASTY)}: derivation report</title>" in page
    assert "from a&amp;b.toml." in page
    assert environment(True) is not environment(False) and isinstance(environment(True), jinja2.Environment)
