"""Regression against workflow/reference.yaml: the scenes, built from workflow/config.yaml,
reproduce every quoted number; and the check itself can fail."""

from __future__ import annotations

import copy
import json

import pytest
from conftest import ROOT

from flutterfriction.config import load_config, scene_params
from flutterfriction.reference import failed, load_reference, run_check, summary_markdown
from flutterfriction.registry import build_scene


@pytest.fixture(scope="module")
def reference():
    return load_reference(ROOT / "workflow" / "reference.yaml")


@pytest.fixture(scope="module")
def recorded():
    """The chapter's parameters of every scene and preset (the shipped record)."""
    from flutterfriction.reference import load_parameters

    return load_parameters(ROOT / "workflow" / "reference_parameters.json")


# The nonlinear rod's cycle, its work-precision study, its Hopf onset and its branch take
# ~2-5 min each; the workflow's check (run by CI on every commit) covers their entries, and
# tests/test_rod_nonlinear.py, tests/test_beck_branch.py their solvers.
WORKFLOW_ONLY = {"beck_limit_cycle", "beck_work_precision", "beck_hopf", "beck_branch"}


@pytest.fixture(scope="module")
def scene_data(reference):
    config = load_config(ROOT / "workflow" / "config.yaml")
    names = {e["scene"] for section in ("quantities", "errata") for e in reference[section]}
    return {n: build_scene(n, scene_params(config, n)) for n in names - WORKFLOW_ONLY}


@pytest.fixture(scope="module")
def testable(reference):
    return {section: [e for e in reference[section] if e["scene"] not in WORKFLOW_ONLY]
            for section in ("quantities", "errata")}


@pytest.mark.slow  # builds every scene (~1-2 min); the workflow's check does the same every run
def test_every_reference_entry_passes(reference, testable, scene_data):
    rows = run_check(testable, scene_data)
    assert not failed(rows), summary_markdown(rows)
    assert sum(r.status == "verified erratum" for r in rows) == len(reference["errata"])


def test_every_entry_documents_its_tolerance(reference):
    for entry in reference["quantities"]:
        if isinstance(entry["quoted"], str):
            continue
        for key in ("tolerance", "agreement"):
            assert entry[key].get("why"), f"{entry['id']}: {key} needs a 'why'"
    for entry in reference["errata"]:
        for key in ("printed", "corrected", "evidence"):
            assert entry.get(key), f"{entry['id']} lacks {key}"


@pytest.mark.slow  # uses every scene's data (built once for the module, ~1-2 min)
def test_check_fails_on_a_wrong_value(testable, scene_data):
    data = copy.deepcopy(scene_data)
    data["eq46"]["quantities"]["gamma_flu"]["value"] = 2.0 * (1 + 1e-9)
    rows = {r.id: r for r in run_check(testable, data)}
    assert rows["eq46_P_flu"].status == "FAIL"


@pytest.mark.slow  # uses every scene's data (built once for the module, ~1-2 min)
def test_check_fails_when_the_methods_disagree(testable, scene_data):
    data = copy.deepcopy(scene_data)
    data["eq47"]["quantities"]["P_flu"]["independent"] = 4.81  # still within the quoted digits
    rows = {r.id: r for r in run_check(testable, data)}
    assert rows["eq47_P_flu"].status == "FAIL"


@pytest.mark.slow  # uses every scene's data (built once for the module, ~1-2 min)
def test_erratum_unverified_when_printed_form_is_right(testable, scene_data):
    data = copy.deepcopy(scene_data)
    e = data["errata_ziegler"]["errata"]["eq39_flutter_sqrt_ka"]
    e["printed"] = e["independent"]
    rows = {r.id: r for r in run_check(testable, data)}
    assert rows["erratum_eq39_flutter_half_width"].status == "UNVERIFIED erratum"


@pytest.mark.slow  # uses every scene's data (built once for the module, ~1-2 min)
def test_categorical_statement_fails_when_regime_differs(testable, scene_data):
    data = copy.deepcopy(scene_data)
    data["fig04"]["quantities"]["regime_flutter"]["value"] = "stable"
    rows = {r.id: r for r in run_check(testable, data)}
    assert rows["fig04_flutter_load_in_flutter_region"].status == "FAIL"


def test_fig04_regimes_are_checked_on_fig04s_own_pendulum():
    """An outside audit: the Fig. 4 entries read scene eq47, so with fig04's own pendulum
    (k1 = k2 = 0.6 N m: its "flutter" load stable) they still passed. They read fig04 now,
    whose parameters decide whether they apply."""
    from flutterfriction.reference import load_reference

    ref = {e["id"]: e for e in load_reference(ROOT / "workflow" / "reference.yaml")["quantities"]}
    for rid in ("fig04_flutter_load_in_flutter_region",
                "fig04_divergence_load_in_divergence_region"):
        assert ref[rid]["scene"] == "fig04"
    import matplotlib.pyplot as plt

    from flutterfriction.config import load_config, scene_params
    from flutterfriction.plotting.ziegler import plot_fig04
    from flutterfriction.scenes.ziegler import fig04

    params = scene_params(load_config(ROOT / "workflow" / "config.yaml"), "fig04")
    own = fig04({**params, "pendulum": {**params["pendulum"], "k1": 0.6, "k2": 0.6}})
    assert own["quantities"]["regime_flutter"]["value"] == "stable"
    fig = plot_fig04({**own, "params": own.get("params", {})})
    texts = " ".join(t.get_text() for t in fig.texts)
    plt.close(fig)
    assert "The chapter's flutter case (upper part), stable for this pendulum" in texts


def test_quick_tolerance_applies_only_at_quick_fidelity():
    """A resolution-dependent entry may be looser at the quick preset, and only there."""
    entry = {"id": "x", "source": "s", "scene": "sc", "key": "k", "quoted": 1.0,
             "tolerance": {"rtol": 1e-4, "why": "paper"}, "agreement": {"rtol": 1e-4, "why": "p"},
             "quick": {"tolerance": {"rtol": 1e-2, "why": "quick mesh, measured 3e-3"}}}
    ref = {"quantities": [entry], "errata": []}
    data = {"sc": {"quantities": {"k": {"value": 1.003, "independent": 1.003, "method": "m",
                                        "independent_method": "i"}}}}
    paper, = run_check(ref, data, "paper")
    quick, = run_check(ref, data, "quick")
    assert paper.status == "FAIL" and quick.status == "pass"
    assert quick.note == "quick-preset tolerance" and "quick-preset" in summary_markdown([quick])
    data["sc"]["quantities"]["k"]["value"] = 1.03  # beyond the quick tolerance too
    assert run_check(ref, data, "quick")[0].status == "FAIL"


def test_quick_block_needs_its_why(tmp_path):
    import yaml

    entry = {"id": "x", "source": "s", "scene": "sc", "key": "k", "quoted": 1.0,
             "quick": {"tolerance": {"rtol": 1e-2}}}
    path = tmp_path / "ref.yaml"
    path.write_text(yaml.safe_dump({"quantities": [entry], "errata": []}))
    with pytest.raises(ValueError, match="quick"):
        load_reference(path)


def _with_tolerance(reference):
    """The first quantity entry with its own tolerance (whatever the file's order)."""
    return next(q for q in reference["quantities"] if "tolerance" in q)


@pytest.mark.parametrize(("edit", "match"), [
    (lambda r: (q := _with_tolerance(r)).update(tolerence=q.pop("tolerance")),
     r"quantities\[\d+\] \(id \w+\): unknown key\(s\) \['tolerence'\]"),
    (lambda r: _with_tolerance(r)["tolerance"].update(atol=float("inf")),
     r"quantities\[\d+\] \(id \w+\): tolerance: atol and rtol must be finite"),
    (lambda r: _with_tolerance(r)["tolerance"].update(atol=0.0, rtol=0.0),
     "needs atol > 0 or rtol > 0"),
    (lambda r: r["errata"][0].pop("key"), r"errata\[0\] \(id erratum_eq1\w+\): 'key'"),
    (lambda r: r["quantities"].append(dict(r["quantities"][0])), "duplicate id"),
    (lambda r: r["quantities"][0].pop("origin"), r"quantities\[0\] \(id \w+\): 'origin' is a "
     "required property"),
    (lambda r: r["quantities"][0].update(origin="chapter"),
     r"quantities\[0\] \(id \w+\): origin: 'chapter' is not one of"),
    (lambda r: next(q for q in r["quantities"] if q["origin"] == "ours"
                    and "beyond" in q["source"]).update(origin="printed"),
     r"origin must be 'ours' for a source beyond the chapter"),
])
def test_reference_file_errors_name_the_entry(reference, edit, match):
    import copy
    import re

    from flutterfriction.reference import reference_problems

    assert reference_problems(reference) == []
    bad = copy.deepcopy(reference)
    edit(bad)
    problems = reference_problems(bad)
    assert any(re.search(match, p) for p in problems), problems


def test_reference_problems_refuse_nan_quotes_unknown_scenes_and_wide_tolerances():
    """Outside audit: a NaN quoted value, an unknown scene and rtol 1e300 (passes anything)
    were accepted; a non-list section raised a raw TypeError."""
    import math

    from flutterfriction.reference import reference_problems
    from flutterfriction.registry import SCENES

    ref = load_reference(ROOT / "workflow" / "reference.yaml")
    assert reference_problems(ref, scenes=SCENES) == []
    bad = copy.deepcopy(ref)
    q = next(e for e in bad["quantities"] if isinstance(e["quoted"], float))
    q["quoted"], q["scene"] = math.nan, "typo"
    q["tolerance"] = {**q["tolerance"], "rtol": 1e300}  # (tolerances may be shared anchors)
    problems = reference_problems(bad, scenes=SCENES)
    assert any("quoted must be a finite number" in p for p in problems)
    assert any("'typo' is not a registered scene" in p for p in problems)
    assert any("rtol must be < 0.5" in p for p in problems)
    assert all(p.startswith(f"quantities[{bad['quantities'].index(q)}] (id {q['id']})")
               for p in problems)
    assert reference_problems({"quantities": 5, "errata": []})  # no TypeError


@pytest.mark.slow
@pytest.mark.parametrize(("edit", "expected"), [
    ({"workflow/reference.yaml": "bogus_top: 1\nquantities: 5\n"}, "unknown key(s) ['bogus_top']"),
    ({"workflow/coverage.yaml": "- {figure: 1, statuss: x}\n"}, "workflow/coverage.yaml: "),
    ({}, "must be in [1, 10000], got 0"),  # with --set-scatter sweep=0
    # an unknown scatter name was accepted silently (an outside audit)
    ({"--set-scatter": "foo=3"}, "--set-scatter: unknown scatter name(s) ['foo']"),
])
def test_the_workflow_refuses_bad_reference_coverage_and_scatter_before_any_job(
        tmp_path, edit, expected):
    """Outside audit: these passed `snakemake -n` and would have failed in the report job, after
    everything else (or, for sweep=0, planned no sweep part at all)."""
    import os
    import shutil
    import subprocess
    import sys

    for part in ("src", "workflow", "notebooks"):
        shutil.copytree(ROOT / part, tmp_path / part,
                        ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    shutil.copy(ROOT / "Snakefile", tmp_path / "Snakefile")
    edit = dict(edit)
    scatter = edit.pop("--set-scatter", "sweep=0") if not edit or "--set-scatter" in edit \
        else None
    for path, text in edit.items():
        (tmp_path / path).write_text(text)
    extra = [] if scatter is None else ["--set-scatter", scatter]
    run = subprocess.run([sys.executable, "-m", "snakemake", "-n", *extra], cwd=tmp_path,
                         env={**os.environ, "PYTHONPATH": str(tmp_path / "src")},
                         capture_output=True, text=True)
    assert run.returncode != 0 and expected in run.stdout + run.stderr
    assert "Traceback" not in run.stdout + run.stderr  # one line (sweep=0 had a traceback)


def _one_quantity(key="k", scene="sc"):
    return {"id": "x", "source": "s", "origin": "printed", "scene": scene, "key": key,
            "quoted": 1.0,
            "tolerance": {"atol": 0.0, "rtol": 1e-4, "why": "w"},
            "agreement": {"atol": 0.0, "rtol": 1e-4, "why": "w"}}


_DATA = {"sc": {"quantities": {"k": {"value": 1.0, "independent": 1.0, "method": "m",
                                     "independent_method": "i"}},
                "errata": {}},
         "other": {"quantities": {"k_other": {"value": 2.0, "independent": 2.0, "method": "m",
                                              "independent_method": "i"}}}}


@pytest.mark.parametrize(("key", "note"), [
    ("bogus_key", "key 'bogus_key' is not among the quantities of scene 'sc' (k)"),
    ("k_other", "key 'k_other' is not among the quantities of scene 'sc' (k); it is one of "
                "scene 'other'"),  # another scene's key
])
def test_an_unknown_key_is_one_fail_line_not_a_key_error(key, note):
    """Outside audit: a reference entry with a bogus key (or one of another scene) passed the
    dry run and the final check job died with KeyError after all the work."""
    ref = {"quantities": [_one_quantity(key)],
           "errata": [{"id": "e", "source": "s", "printed": "p", "corrected": "c",
                       "evidence": "v", "scene": "sc", "key": "nope",
                       "agreement": {"atol": 0.0, "rtol": 1e-4, "why": "w"}}]}
    rows = run_check(ref, _DATA)
    assert [(r.id, r.status, r.note) for r in rows] == [
        ("x", "FAIL", note),
        ("e", "FAIL", "key 'nope' is not among the errata of scene 'sc' (it has none)")]
    assert failed(rows) == rows
    md = summary_markdown(rows)
    assert f"FAIL ({note})" in md and "**2 of 2 entries FAIL.**" in md
    row, = run_check({"quantities": [_one_quantity(scene="gone")], "errata": []}, _DATA)
    assert row.status == "FAIL" and row.note == "scene 'gone' has no data in this run"


def test_a_key_given_twice_in_the_reference_file_is_refused(tmp_path):
    """Outside audit: `quoted:` given twice in an entry kept the last silently."""
    from flutterfriction.reference import reference_file_problems

    path = tmp_path / "reference.yaml"
    path.write_text("quantities:\n  - id: x\n    source: s\n    origin: ours\n"
                    "    scene: eq25\n    key: k\n    quoted: 1.0\n    quoted: 2.0\n"
                    "    tolerance: {atol: 0, rtol: 1.0e-4, why: w}\n"
                    "    agreement: {atol: 0, rtol: 1.0e-4, why: w}\nerrata: []\n")
    assert reference_file_problems(path) == [
        f"{path}: quantities.0: key 'quoted' given twice at line 8 (first at line 7; YAML "
        "would keep the last silently)"]
    with pytest.raises(ValueError, match="key 'quoted' given twice at line 8"):
        load_reference(path)


def test_an_empty_reference_and_a_quoted_number_as_a_string_are_refused():
    """Outside audit: `quantities: []` with `errata: []` passed (the check then checked
    nothing); `quoted: "0.0911"` passed and showed FAIL with no error value."""
    from flutterfriction.reference import reference_problems

    assert reference_problems({"quantities": [], "errata": []}) == [
        "quantities and errata are both empty: the check would check nothing (list at least "
        "one entry)"]
    assert reference_problems({"quantities": [_one_quantity()], "errata": []}) == []
    entry = {**_one_quantity(), "quoted": "0.0911"}
    assert reference_problems({"quantities": [entry], "errata": []}) == [
        "quantities[0] (id x): quoted: '0.0911' is a number written as a string: write it "
        "unquoted (a string is a categorical statement such as 'flutter', compared word for "
        "word, with no tolerance)"]
    entry = {**_one_quantity(), "quoted": "flutter"}  # a categorical statement stays allowed
    assert reference_problems({"quantities": [entry], "errata": []}) == []


def test_recorded_parameters_are_the_shipped_configuration():
    """workflow/reference_parameters.json records the parameters every quoted value belongs
    to; it must be what the shipped configuration resolves, for every preset (after a
    deliberate change of a scene's parameters, re-record: python -m flutterfriction.reference
    and re-verify that scene's reference entries)."""
    from flutterfriction.config import load_config
    from flutterfriction.reference import load_parameters, parameter_changes, record_parameters

    shipped = record_parameters(load_config(ROOT / "workflow" / "config.yaml"))
    assert parameter_changes(load_parameters(ROOT / "workflow" / "reference_parameters.json"),
                             shipped) == []


def test_a_scene_with_other_parameters_is_not_applicable_not_failed(reference, recorded):
    """A researcher's own pendulum in eq47 (k1 = 0.25): the chapter's 4.8038 N does not apply,
    so the entry is 'not applicable', naming the changed key, and does not fail the run (it
    failed it, unexplained: an outside audit); the scenes left alone are still checked."""
    from flutterfriction.reference import NOT_APPLICABLE, failed, run_check

    entry = next(e for e in reference["quantities"] if e["id"] == "eq47_P_flu")
    params = json.loads(json.dumps(recorded["paper"]["eq47"]))
    params["pendulum"]["k1"] = 0.25
    data = {"eq47": {"scene": "eq47", "params": params,
                     "quantities": {entry["key"]: {"value": 4.7476, "independent": 4.7476,
                                                   "method": "m", "independent_method": "i",
                                                   "unit": "N"}}}}
    rows = run_check({"quantities": [entry]}, data, "paper", recorded)
    assert rows[0].status == NOT_APPLICABLE and "pendulum.k1: 0.189 -> 0.25" in rows[0].note
    assert rows[0].reproduced == 4.7476  # your own value, shown
    assert failed(rows) == []
    # ... but its two methods are still compared: a disagreement fails (an outside audit: a
    # viscous pendulum computed as undamped passed, "flutter" against the independent "stable")
    q = data["eq47"]["quantities"][entry["key"]]
    q["independent"] = 4.80
    rows = run_check({"quantities": [entry]}, data, "paper", recorded)
    assert rows[0].status == "FAIL" and "two methods disagree" in rows[0].note
    assert rows[0].agreement > 1
    q["independent"] = 4.7476
    # the same data with the chapter's parameters: checked, and 4.7476 N fails
    data["eq47"]["params"] = recorded["paper"]["eq47"]
    assert [r.status for r in run_check({"quantities": [entry]}, data, "paper", recorded)] == [
        "FAIL"]
    # a resolution key (one a preset overrides: n_points) changed: still the chapter's values,
    # checked (a smoother curve must not make the chapter's loads 'not applicable')
    data["eq47"]["params"] = dict(recorded["paper"]["eq47"], n_points=2001)
    assert "n_points" in recorded["resolution_keys"]["eq47"]
    assert [r.status for r in run_check({"quantities": [entry]}, data, "paper", recorded)] == [
        "FAIL"]


def test_numerical_settings_no_preset_overrides_keep_the_entries_checked():
    """An outside audit: fig10's fe_elements 32 -> 48, elastica's load_steps, localization's
    n_search and fig05's plotted gamma_max made 28 entries 'not applicable' with unchanged
    values: the numerical settings of every scene are resolution keys too."""
    from flutterfriction.reference import load_parameters, load_reference, run_check

    recorded = load_parameters(ROOT / "workflow" / "reference_parameters.json")
    for scene, key in (("fig10", "fe_elements"), ("elastica", "load_steps"),
                       ("localization_directions", "n_search"), ("fig05", "gamma_max")):
        assert key in recorded["resolution_keys"][scene]
    reference = load_reference(ROOT / "workflow" / "reference.yaml")
    entry = next(e for e in reference["quantities"] if e["scene"] == "fig10")
    params = dict(recorded["paper"]["fig10"], fe_elements=48)
    data = {"fig10": {"scene": "fig10", "params": params, "quantities": {entry["key"]: {
        "value": -1.0, "independent": -1.0, "method": "m", "independent_method": "i",
        "unit": ""}}}}
    assert [r.status for r in run_check({"quantities": [entry]}, data, "paper", recorded)] == [
        "FAIL"]  # checked (and a wrong value fails), not 'not applicable'


def test_figures_name_a_chapter_list_only_for_its_parameters():
    """A figure of a researcher's own pendulum or rod must not say 'list (47)' (an outside
    audit: eq47's title did): the recorded chapter parameters give the list's name, others
    'your own pendulum (...)' with the values."""
    from flutterfriction.plotting import list47, list119
    from flutterfriction.reference import load_parameters

    recorded = load_parameters(ROOT / "workflow" / "reference_parameters.json")["paper"]
    assert list47({"params": recorded["eq47"]}) == "list (47)"
    assert list119({"params": recorded["fig11"]}) == "list (119)"
    own = json.loads(json.dumps(recorded["eq47"]))
    own["pendulum"]["k1"] = 0.25
    assert list47({"params": own}).startswith("your own pendulum (")
    assert "k1 = 0.25 N m" in list47({"params": own})
    rod = json.loads(json.dumps(recorded["fig11"]))
    rod["rod"]["tip_mass"] = 0.02  # a key list (119) does not have, not zero
    assert list119({"params": rod}).startswith("your own rod (")


def test_notebooks_note_the_scenes_computed_with_your_own_parameters():
    """The notebooks' hand-written prose describes the chapter's parameters; a scene run with
    other physical parameters is named at the top of its notebook, with the changed keys
    (a resolution key, which leaves the chapter's values in force, is not a change)."""
    import json

    from flutterfriction.config import load_config, scene_params
    from flutterfriction.reference import own_parameters_note, own_parameters_summary

    config = load_config(ROOT / "workflow" / "config.yaml")
    params = json.loads(json.dumps(scene_params(config, "fig13")))
    record = ROOT / "workflow" / "reference_parameters.json"
    assert own_parameters_note({"fig13": params}, record) == ""
    quick = json.loads(json.dumps(scene_params(config | {"fidelity": "quick"}, "fig13")))
    assert own_parameters_note({"fig13": quick}, record) == ""
    note = own_parameters_note({"fig13": {**params, "load_factor": 2.0}}, record)
    assert note.startswith("**Computed with your own parameters.**")
    assert "- `fig13`: load_factor: 1.5 -> 2.0" in note
    assert own_parameters_summary({"fig13": params}, record).startswith("None: every scene")
    assert own_parameters_summary({"fig13": {**params, "load_factor": 2.0}}, record) == note
    for nb in sorted((ROOT / "notebooks").glob("*.py")):
        text = nb.read_text()
        assert "NOTE.update(Markdown(own_parameters_note(READ)))" in text, nb.name
        assert "display(Markdown(own_parameters_summary(READ)))" in text, nb.name
        assert 'READ[name] = data.get("params")' in text, nb.name


def test_an_atol_that_checks_nothing_and_an_empty_key_are_refused():
    """Outside audit: `atol: 1.0e+300` (passes any value) and `key: ''` were accepted. atol is
    bounded as rtol is: below 0.5 |quoted| (the file's largest: 0.08), or at most 0.5 for a
    quoted 0 (the file's largest: half a unit of a count)."""
    from flutterfriction.reference import reference_problems

    entry = {**_one_quantity(), "quoted": 2.0}
    entry["tolerance"] = {"atol": 1.0e300, "rtol": 0.0, "why": "w"}
    assert reference_problems({"quantities": [entry], "errata": []}) == [
        "quantities[0] (id x): tolerance: atol must be < 0.5 |quoted| = 1 (a tolerance that "
        "wide checks nothing), got 1e+300"]
    entry = {**_one_quantity(), "quoted": 0.0}
    entry["agreement"] = {"atol": 0.6, "rtol": 0.0, "why": "w"}
    assert reference_problems({"quantities": [entry], "errata": []}) == [
        "quantities[0] (id x): agreement: atol must be <= 0.5 for a quoted 0 (half a unit of a "
        "count), got 0.6"]
    entry = {**_one_quantity(), "quoted": 2.0}
    entry["tolerance"] = {"atol": 0.999, "rtol": 0.0, "why": "w"}  # just inside
    assert reference_problems({"quantities": [entry], "errata": []}) == []
    assert reference_problems({"quantities": [_one_quantity(key="")], "errata": []}) == [
        "quantities[0] (id x): key must be a non-empty string"]


def test_unknown_top_level_keys_leave_out_the_anchors_and_a_yaml_error_is_one_line(
        reference, tmp_path):
    """Outside audit: an unknown top-level key listed the ten `_...` anchor keys as unknown
    with it; a YAML syntax error in load_reference was a bare yaml exception."""
    from flutterfriction.errors import ParameterError
    from flutterfriction.reference import reference_problems

    bad = {**copy.deepcopy(reference), "bogus": 1}
    assert sum(k.startswith("_") for k in bad) == 10
    assert reference_problems(bad) == [
        "(top level): unknown key(s) ['bogus']; allowed: ['errata', 'quantities'] and keys "
        "starting with '_' (YAML anchors)"]
    path = tmp_path / "reference.yaml"
    path.write_text("quantities: [\n  - id: x\nerrata: []\n")
    with pytest.raises(ParameterError) as info:
        load_reference(path)
    assert str(info.value) == (f"{path}: invalid reference file: line 2, column 3: YAML syntax "
                               "error: did not find expected node content")


def test_a_number_quoted_for_a_word_is_a_failed_row_not_a_value_error():
    """Outside audit: a numeric `quoted` on a key whose reproduced value is a word (a regime)
    made run_check die with a bare ValueError at the end of the run."""
    data = {"sc": {"quantities": {"k": {"value": "flutter", "independent": "flutter",
                                        "method": "m", "independent_method": "i"}}}}
    row, = run_check({"quantities": [_one_quantity()], "errata": []}, data)
    assert (row.status, row.error, row.note) == (
        "FAIL", None, "the reference quotes a number, the scene's value 'flutter' and "
                      "independent 'flutter' is not one (key 'k' of scene 'sc')")
    assert failed([row]) == [row]


@pytest.mark.parametrize(("content", "message"), [
    ('{"paper": {"sc": {"a": NaN}}}', "invalid recorded parameters: paper.sc.a must be a "
                                      "finite number, got nan"),
    ('{"paper": {"sc": {"n": [1, Infinity]}}}', "invalid recorded parameters: paper.sc.n[1] "
                                                "must be a finite number, got inf"),
    ("[1, 2]", "invalid recorded parameters: must be a non-empty mapping of preset -> scene "
               "-> parameters, got list"),
    ('{"paper": {"sc": [1]}}', "invalid recorded parameters: paper.sc must be a mapping of "
                               "parameters, got list"),
    ('{"resolution_keys": {"sc": "n_points"}}', "invalid recorded parameters: "
                                                "resolution_keys.sc must be a list of key names"),
    ("garbage{", "not valid JSON: line 1, column 1: Expecting value"),
])
def test_the_recorded_parameters_are_validated_in_one_line(tmp_path, content, message):
    """Outside audit: workflow/reference_parameters.json was never validated: NaN and a list
    were accepted (a list then raised a bare AttributeError in run_check), garbage a bare
    JSONDecodeError."""
    from flutterfriction.errors import ParameterError
    from flutterfriction.reference import load_parameters

    path = tmp_path / "reference_parameters.json"
    path.write_text(content)
    with pytest.raises(ParameterError) as info:
        load_parameters(path)
    assert str(info.value).startswith(f"{path}: {message}")
    assert "\n" not in str(info.value)
    with pytest.raises(ParameterError, match=r"^parameters \(the recorded parameters\): must "
                                             r"be a non-empty mapping"):
        run_check({"quantities": [_one_quantity()], "errata": []}, _DATA, parameters=[1, 2])
    assert set(load_parameters(ROOT / "workflow" / "reference_parameters.json")) == {
        "paper", "quick", "resolution_keys"}


def test_wrap_items_breaks_between_items_only():
    """A figure title's parameter list on short lines, never "0.1" on one line and "m" on
    the next; an item longer than the width stands on its own line."""
    from flutterfriction.plotting import wrap_items

    text = "l1 = l2 = 0.1 m, d = 0.1 m, h = 0 m, m1 = m2 = 0.2 kg, m3 = 0 kg, k1 = k2 = 0.189 N m"
    lines = wrap_items(text, 40).split("\n")
    assert len(lines) == 3 and all(len(line) <= 40 for line in lines)
    assert ", ".join(line.rstrip(",") for line in lines) == text
    assert wrap_items("a, " + "b" * 50 + ", c", 10).split("\n") == ["a,", "b" * 50 + ",", "c"]


def test_every_quantity_names_the_origin_of_its_value_and_the_summaries_count_them(reference):
    """``origin`` (printed / formula / stated / ours) is one of ORIGINS, as the schema lists
    them; a categorical word is never "printed" or "formula" (no digits to compare); and the
    check's summary and the report count the quantities by origin."""
    from flutterfriction.config import safe_load
    from flutterfriction.reference import ORIGINS, REFERENCE_SCHEMA, CheckRow, origins_sentence

    with open(REFERENCE_SCHEMA, encoding="utf-8") as fh:
        enum = safe_load(fh)["$defs"]["quantity"]["properties"]["origin"]["enum"]
    assert enum == list(ORIGINS)
    origins = [q["origin"] for q in reference["quantities"]]
    assert set(origins) == set(ORIGINS)
    for q in reference["quantities"]:
        if isinstance(q["quoted"], str):
            assert q["origin"] in ("stated", "ours"), q["id"]
    rows = [CheckRow(id=q["id"], kind="quantity", source=q["source"], quoted=q["quoted"],
                     unit="", reproduced=None, independent=None, method="",
                     independent_method="", error=None, agreement=None, status="pass",
                     origin=q["origin"]) for q in reference["quantities"]]
    sentence = origins_sentence(rows)
    assert sentence.startswith(f"The {len(rows)} quantities by the origin")
    for key, words in ORIGINS.items():
        assert f"{origins.count(key)} {words}" in sentence
    assert sentence in summary_markdown(rows)


def test_the_chapters_special_case_formulas_are_not_applied_to_a_researchers_pendulum(
        reference, recorded):
    """An outside review: with its own (unequal-rod, unsymmetric) pendulum the run failed on
    correct numbers: eq. (25)'s (3 - sqrt 5)/2 (the equal rods') was eq25's independent
    method, and eq. (54)'s 4/3 + eps^2/2 (the symmetric pendulum's) fig05's primary. The
    scenes now compute those quantities only where the chapter's formula holds, so the
    entries are not applicable (not failed) for another pendulum and still checked for the
    chapter's."""
    from flutterfriction.reference import NOT_APPLICABLE, failed, run_check

    config = load_config(ROOT / "workflow" / "config.yaml")
    mine = {"l1": 0.15, "l2": 0.12, "d": 0.1, "h": 0.05, "m1": 0.4, "m2": 0.08, "m3": 0.1,
            "k1": 0.3, "k2": 0.2}
    ids = {"eq25": ["eq25_H_cr_exact", "eq25_H_cr_approx"],
           "fig05": ["eq54_closed_form_eps0.1", "eq54_closed_form_eps0.5"]}
    for scene, names in ids.items():
        entries = [e for e in reference["quantities"] if e["id"] in names]
        chapter = scene_params(config, scene)
        data = {scene: build_scene(scene, chapter)}
        rows = run_check({"quantities": entries, "errata": []}, data, "paper", recorded)
        assert [r.status for r in rows] == ["pass"] * len(names)
        own = dict(chapter, pendulum=mine)
        data = {scene: build_scene(scene, own)}
        assert not any(e["key"] in data[scene]["quantities"] for e in entries
                       if e["id"] != "eq25_H_cr_approx")  # (its key is eq. 22's, general)
        rows = run_check({"quantities": entries, "errata": []}, data, "paper", recorded)
        assert [r.status for r in rows] == [NOT_APPLICABLE] * len(names) and not failed(rows)


@pytest.mark.parametrize("case, edit, problem", [
    ("not JSON", lambda d: "{not json", r"not valid JSON: line 1, column 2"),
    ("a key twice", lambda d: '{"paper": {}, "paper": {}}', r"key 'paper' written twice"),
    ("an unknown preset", lambda d: d.update(fast={}), r"unknown preset 'fast'"),
    ("a deleted preset", lambda d: d.pop("quick"), r"preset 'quick' is not recorded"),
    ("an unknown scene", lambda d: d["paper"].update(eq99={}), r"paper\.eq99: no such scene"),
    ("a deleted scene", lambda d: d["paper"].pop("eq25"),
     r"paper: scene 'eq25', which .*reference\.yaml checks, is not recorded"),
    ("a string", lambda d: d["paper"]["eq25"].update(n_points="801"),
     r"paper: scenes\.eq25\.n_points: '801' is a string"),
])
def test_the_parameter_record_is_checked_at_the_workflows_start(tmp_path, case, edit, problem):
    """An outside audit: workflow/reference_parameters.json was read only by the last jobs,
    and these passed there (a deleted scene or preset made a user's own parameters count as
    the chapter's). Now the configuration's check (every snakemake call, before any job)
    refuses each in one line naming the file."""
    import re

    from flutterfriction.reference import parameters_file_problems
    from flutterfriction.registry import SCENES

    shipped = ROOT / "workflow" / "reference_parameters.json"
    files = {k: ROOT / "workflow" / v for k, v in (("reference", "reference.yaml"),
             ("shipped", "config.yaml"), ("schema_path", "schemas/config.schema.yaml"))}
    assert parameters_file_problems(shipped, scenes=SCENES, **files) == []
    record = json.loads(shipped.read_text())
    text = edit(record)
    path = tmp_path / "record.json"
    path.write_text(text if isinstance(text, str) else json.dumps(record))
    problems = parameters_file_problems(path, scenes=SCENES, **files)
    assert len(problems) == 1 and re.search(problem, problems[0]), problems
    assert problems[0].startswith(f"{path}: ")


def test_re_recording_the_parameters_refuses_arguments_and_a_bad_configuration(
        tmp_path, monkeypatch, capsys):
    """`python -m flutterfriction.reference` re-records workflow/reference_parameters.json
    from workflow/config.yaml. It took any arguments silently, and recorded a configuration
    that does not validate (it would then be the chapter's parameters for every check)."""
    import shutil

    from flutterfriction.reference import _record_main

    assert _record_main(["--bogus"]) == 2
    assert "takes no arguments" in capsys.readouterr().err
    shutil.copytree(ROOT / "workflow", tmp_path / "workflow")
    monkeypatch.chdir(tmp_path)
    record = tmp_path / "workflow" / "reference_parameters.json"
    before = record.read_text()
    assert _record_main([]) == 0 and record.read_text() == before  # the shipped one: the same
    config = tmp_path / "workflow" / "config.yaml"
    config.write_text(config.read_text().replace("    p_test: 3.0\n", "    p_test: 3.0e+200\n"))
    record.write_text("{}")
    assert _record_main([]) == 2
    assert "p_test: 3e+200 is greater than the maximum of 1000" in capsys.readouterr().err
    assert record.read_text() == "{}"  # nothing written
