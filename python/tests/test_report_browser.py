"""`lpm simulate --report` in a real browser: headless Chromium (Debian's
`chromium`, which python/test.sh installs) renders report.html without a
console message (a resource it cannot load would be one), and its
screenshot has the plots' curves drawn in their colours."""

import shutil
import struct
import subprocess
import zlib

import pytest

from conftest import SPECS, run_lpm

# The first series colour of the plots (plotters' palette, as plots.svg
# writes it), in RGB; nothing else on the page has it.
CURVE_BLUE = (0x1F, 0x77, 0xB4)


def read_png(path):
    """Width, height and rows of RGB triples of an 8-bit RGB or RGBA PNG."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    at, idat, header = 8, b"", None
    while at < len(data):
        (length,) = struct.unpack(">I", data[at : at + 4])
        kind, body = data[at + 4 : at + 8], data[at + 8 : at + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0, header
    channels = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up, up_left = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 0xFF
            elif kind == 2:
                line[i] = (line[i] + up) & 0xFF
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 0xFF
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                predictor = left if pa <= pb and pa <= pc else up if pb <= pc else up_left
                line[i] = (line[i] + predictor) & 0xFF
        rows.append([tuple(line[x * channels : x * channels + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def near(pixel, colour, tolerance=40):
    return all(abs(a - b) <= tolerance for a, b in zip(pixel, colour))


def test_the_report_renders_in_chromium_without_console_messages_and_with_its_plots(tmp_path):
    browser = shutil.which("chromium")
    if browser is None:
        pytest.fail("no chromium on PATH: python/test.sh installs Debian's chromium package")
    # With a test: the report rates the run against it and overlays the pair.
    run_lpm(
        "simulate", SPECS / "yaris_double_pendulum.lpm", "--report", "--out", tmp_path,
        "--test", SPECS / "data" / "yaris_pulse.csv", "--test-channel", "deceleration=r_ddot",
    )
    page, shot = tmp_path / "report.html", tmp_path / "report.png"
    done = subprocess.run(
        [
            browser,
            "--headless=new",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--window-size=1200,3400",
            "--enable-logging=stderr",
            "--v=0",
            f"--screenshot={shot}",
            page.as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    console = [line for line in done.stderr.splitlines() if "CONSOLE" in line]
    assert console == [], console
    width, height, rows = read_png(shot)
    assert (width, height) == (1200, 3400)
    blue = sum(near(p, CURVE_BLUE) for row in rows for p in row)
    # The curves are drawn: 2151 pixels of their blue in the plots on
    # 2026-12-02, 3659 with the test's overlay below them on 2026-12-03
    # (its reference curve is blue too); the same page with its <svg>s
    # removed has none.
    assert blue > 2600, f"{blue} blue pixels"
