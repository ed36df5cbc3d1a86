"""tcasim.study on a two-worker LocalCluster (threads: quick to start): a grid of TCA offset x
temperature x tip mass gives one CSV row per point, in point order, with the numbers of
tcasim.solve; a failing point keeps its row with the error message."""
import csv
import json

import pytest

import tcasim
from conftest import SCENARIO_DIR

pytest.importorskip("dask.distributed")
from tcasim import study  # noqa: E402

BASE = SCENARIO_DIR / "square-manipulator.json"


def test_set_path_edits_documents_by_key_path():
    d = json.loads(BASE.read_text())
    study.set_path(d, "actuators[u-tca].routing.offset_m[0]", 0.002)
    study.set_path(d, "actuators[0].drive.temperature_degC", 70)
    study.set_path(d, "gravity_m_s2[2]", -9.81)
    assert d["actuators"][0]["routing"]["offset_m"][0] == 0.002
    assert d["actuators"][0]["drive"]["temperature_degC"] == 70
    with pytest.raises(tcasim.InputError) as e:
        study.set_path(d, "actuators[nope].count", 2)
    assert e.value.key == "actuators[nope].count"
    assert study.grid(a=[1, 2], b=[3]) == [{"a": 1, "b": 3}, {"a": 2, "b": 3}]


def test_a_grid_on_two_workers_gives_one_row_per_point(tmp_path, capsys):
    grid = {
        "actuators[u-tca].routing.offset_m[0]": [0.002, 0.003],
        "actuators[u-tca].drive.temperature_degC": [60, 90, -400],  # -400: an input error
        "tip_mass_g": [0, 1],
    }
    out = tmp_path / "study.csv"
    rows = study.run_study(BASE, grid, setters={"tip_mass_g": study.tip_mass_g}, out=out,
                           n_workers=2, processes=False, batch_size=2)
    assert len(rows) == 12
    with open(out) as f:
        table = list(csv.DictReader(f))
    assert len(table) == 12
    assert "tcasim study: 12/12 points, 4 failed" in capsys.readouterr().err
    for row, line, point in zip(rows, table, study.grid(**grid)):
        for k, v in point.items():
            assert row[k] == v and float(line[k]) == v
        if point["actuators[u-tca].drive.temperature_degC"] == -400:
            assert row["error"].startswith("InputError: actuators[0].drive.temperature_degC = -400")
            assert line["converged"] == "0" and line["error"] == row["error"]
            continue
        assert row["error"] == "" and line["converged"] == "1"
        # The same numbers as a direct solve (the CSV keeps every digit).
        d = json.loads(BASE.read_text())
        study.set_path(d, "actuators[0].routing.offset_m[0]", point["actuators[u-tca].routing.offset_m[0]"])
        study.set_path(d, "actuators[0].drive.temperature_degC", point["actuators[u-tca].drive.temperature_degC"])
        study.tip_mass_g(d, point["tip_mass_g"])
        r = tcasim.solve(d)
        assert [float(line[f"tip_{c}_m"]) for c in "xyz"] == list(r.tip_position_m)
        assert float(line["u-tca_tension_N"]) == r.actuators[0]["tension_N"]


def test_a_list_of_scenarios_with_both_methods(tmp_path):
    files = [SCENARIO_DIR / "circular-manipulator.json", SCENARIO_DIR / "steel-4-tendon.json"]
    rows = study.run_study(scenarios=files, points=[{"method": "cosserat"}, {"method": "fe"}],
                           n_workers=2, processes=False, progress=False)
    assert [(r["scenario_file"], r["method"]) for r in rows] == [
        (str(files[0]), "cosserat"), (str(files[0]), "fe"),
        (str(files[1]), "cosserat"), (str(files[1]), "fe")]
    assert all(r["converged"] and r["error"] == "" for r in rows)
