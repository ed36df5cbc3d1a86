"""A small validate.sh output folder for the report tests: two programs, real PNG plots,
known tables, gates (optionally one failed). Standard library only."""
import struct
import zlib
from pathlib import Path


def write_png(path, width=120, height=80, rgb=(40, 110, 200)):
    """A valid RGB PNG of one colour."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    Path(path).write_bytes(png)


def write(path, text):
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(text)


def make_fixture(out, failing_gate=False, gates_per_program=30):
    """Fills `out` like scripts/validate.sh would; returns the number of gates."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    write(out / "timing.csv", "program,exit_code,seconds,plot_script,plot_exit_code,plot_seconds\n"
          f"validate_fig5_tca,{1 if failing_gate else 0},0.40,plot_fig5.py,0,2.1\n"
          "validate_shapes,0,0.08,plot_shapes.py,0,3.7\n")
    write(out / "run_info.csv", "key,value\nstarted_utc,2026-01-01T00:00:00Z\ntotal_seconds,18\n"
          "build_seconds,1\nbuild_dir,/tmp/build\nbuild_type,Release\njobs,2\n")
    lines = ["program,gate,measured,bound,passed"]
    for k in range(gates_per_program):
        passed = 0 if (failing_gate and k == 7) else 1
        lines.append(f'validate_fig5_tca,"curve {k}: elongation non-decreasing, a long gate name that wraps",'
                     f"{k} decreases,0 decreases,{passed}")
    write(out / "validate_fig5_tca" / "gates.csv", "\n".join(lines) + "\n")
    write(out / "validate_fig5_tca" / "fig5_table.csv",
          "tca,load_g,material,f12_form,onset_temperature_degC,elongation_at_160_degC_m\n"
          "three-thread,7.5,silver-nylon-sun2022,paper,37.8293,0.031908147095887976\n"
          "four-thread,15,silver-nylon-castigliano,castigliano,30.9517,0.05676728768822317\n")
    write_png(out / "validate_fig5_tca" / "fig5.png", 900, 560)
    write(out / "validate_fig5_tca" / "log.txt", "Step 1: curves\n")
    lines = ["program,gate,measured,bound,passed"]
    for k in range(gates_per_program):
        lines.append(f"validate_shapes,scenario-{k}: converges,converged,converged,1")
    lines.append('validate_shapes,"s: observed order of the imbalance, 16 -> 32 steps",3.997,"in [3.5, 4.5]",1')
    write(out / "validate_shapes" / "gates.csv", "\n".join(lines) + "\n")
    write(out / "validate_shapes" / "shapes_summary.csv",
          "scenario,status,iterations,tip_x_m,tip_z_m,wall_time_s,reason\n"
          "a,converged,9,-2.7796687959e-02,-5.43873348e-03,0.0038,\nb,converged,7,1e-3,2e-2,0.0029,\n")
    for name in ("a", "b", "c"):
        write_png(out / "validate_shapes" / f"{name}_shape.png", 400, 300, (200, 80, 40))
    return 2 * gates_per_program + 1
