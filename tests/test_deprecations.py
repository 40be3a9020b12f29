"""Names renamed by the seams issue still work, each with a DeprecationWarning naming what replaced it."""

from __future__ import annotations

import importlib

import pytest

from symjac import load_robot


@pytest.mark.parametrize(("module", "old", "new"), [
    ("symjac.printing.document", "DHTable", "ParameterTable"),
    ("symjac.printing", "DHTable", "ParameterTable"),
    ("symjac.printing.tables", "dh_rows", "parameter_rows"),
    ("symjac.printing.tables", "dh_headers", "parameter_headers"),
    ("symjac.printing.tables", "dh_table_text", "parameter_table_text"),
    ("symjac.printing.tables", "dh_table_latex", "parameter_table_latex"),
    ("symjac.report.content", "dh_table_html", "parameter_table_html"),
    ("symjac.printing.prose", "dh_caption", "table_caption"),
])
def test_an_old_name_is_the_new_object_with_a_warning(module, old, new):
    loaded = importlib.import_module(module)
    with pytest.warns(DeprecationWarning, match=new):
        value = getattr(loaded, old)
    assert value is getattr(loaded, new)


def test_an_unknown_name_is_still_an_attribute_error():
    from symjac.printing import tables

    with pytest.raises(AttributeError, match="no attribute 'dh_nothing'"):
        _ = tables.dh_nothing


def test_show_data_still_gives_the_table_and_the_transforms():
    from symjac.printing.json import show_data

    robot = load_robot("planar2r")
    with pytest.warns(DeprecationWarning, match="document_data"):
        data = show_data(robot, {})
    assert data["parameter_table"] == data["dh_table"] and len(data["dh_table"]) == 2


def test_describe_with_a_robot_still_describes_it():
    from symjac.codegen.module import ModuleRequest, describe

    robot = load_robot("planar2r")
    with pytest.warns(DeprecationWarning):
        old = describe(robot, "python")
    assert old == describe(ModuleRequest(robot, "python"))
