r"""A robot's whole derivation as one self-contained page for the browser (``symjac report ROBOT -o page.html``).

:mod:`.page` assembles it: :mod:`.content` lays out the DH table, transforms, forward kinematics and Jacobians (and
checks that the four derivation methods agree) through :mod:`symjac.printing.mathml` (MathML Core in textbook
shorthand, each equation kept within the page width), :mod:`symjac.analysis.manipulability_map` computes the
manipulability map, the exact singular curves and the joint rates along a path through a singularity, and
:mod:`.figures` draws them as inline SVG with matplotlib (an optional dependency: ``pip install 'symjac[report]'``).
"""

from symjac.report.page import derivation_report

__all__ = ["derivation_report"]
