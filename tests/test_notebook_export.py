"""Executed notebooks as offline HTML: math as MathML, code folded, figures linked, no script
from the network."""

import base64
import re

import pytest

from flutterfriction.notebook_export import fmt, math_to_mathml, quantities_table


def test_inline_and_display_math_become_mathml_and_code_is_left_alone():
    pytest.importorskip("latex2mathml")
    out = math_to_mathml("a $x_1$ and\n$$\\frac{a}{b}$$ but `$y$` and a price of $5 and $6.")
    assert out.count("<math") == 2 and 'display="block"' in out and 'display="inline"' in out
    assert "`$y$`" in out and "$5 and $6" in out
    # inline math may run over a line break of the source, not over a paragraph
    assert "<math" in math_to_mathml("read $\\mathbf{M}\n\\alpha = 0$ here")
    assert "<math" not in math_to_mathml("a $5\n\nand 6$ b")


def test_quantities_table_rounds_and_states_units():
    q = {"P_flu": {"value": 4.80381200884, "independent": 4.80381200891, "unit": "N",
                   "method": "eig", "independent_method": "closed |form|"},
         "kind": {"value": "flutter", "independent": "flutter", "unit": "",
                  "method": "a", "independent_method": "b"}}
    table = quantities_table(q, digits=6)
    assert "| P_flu | 4.80381 | N | eig | 4.80381 | closed \\|form\\| | 1.5e-11 |" in table
    assert "| kind | flutter |" in table
    assert fmt(1 / 3, 3) == "0.333" and fmt("x") == "x"


def test_quantities_table_gives_an_absolute_difference_against_an_exact_zero():
    # a residual of 8.7e-16 against its exact 0: the relative difference would always be 1
    q = {"triple_coalescence": {"value": 8.7e-16, "independent": 0.0, "unit": "",
                                "method": "a", "independent_method": "exact"}}
    assert quantities_table(q).endswith("| 8.7e-16 (abs.) |")


def test_a_notebook_exports_offline_with_code_folded_and_figures_linked(tmp_path):
    pytest.importorskip("latex2mathml")
    pytest.importorskip("nbconvert")
    import nbformat

    from flutterfriction.notebook_export import export_notebook

    png = b"\x89PNG\r\n\x1a\nnot really a png"
    (tmp_path / "figA.png").write_bytes(png)
    nb = nbformat.v4.new_notebook()
    code = nbformat.v4.new_code_cell("show('figA')")
    code.outputs = [nbformat.v4.new_output(
        "display_data", data={"image/png": base64.b64encode(png).decode()},
        metadata={"image/png": {"width": 480}}),
        nbformat.v4.new_output("display_data", data={"text/markdown": "load $P_{flu}$ = 4.8 N"})]
    nb.cells = [nbformat.v4.new_markdown_cell("# T\n\nEq. $\\alpha_1 = 0$."), code]
    page = export_notebook(nb, [tmp_path], "../figures")
    assert not re.search(r"<script[^>]*src=", page)  # nothing from the network
    assert "mathjax" not in page.lower()
    assert page.count("<math") == 2
    fold = page.index('<details class="code-fold"><summary>code</summary>')
    assert fold < page.index(">show<") < page.index("</details>", fold)  # the code, folded
    assert 'src="../figures/figA.png"' in page and '<img src="data:image/png' not in page


def test_warming_the_exporter_leaves_the_next_export_unchanged(tmp_path):
    """The notebook job warms the exporter up while its kernel starts: the page exported after
    the warm-up is the page exported before it."""
    pytest.importorskip("latex2mathml")
    pytest.importorskip("nbconvert")
    import nbformat

    from flutterfriction.notebook_export import export_notebook, warm_exporter

    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# T\n\nEq. $\\beta = 1$."),
                nbformat.v4.new_code_cell("x = 1", id="c2")]
    nb.cells[0].id = "c1"
    before = export_notebook(nb, [tmp_path])
    warm_exporter()
    assert export_notebook(nb, [tmp_path]) == before
