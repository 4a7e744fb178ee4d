"""Launch-monitor exports (mcrun.run.monitors): one fixture per format in ``tests/data/monitors``,
written as the devices and apps write them (a BOM, a ``sep=`` line, a unit row, units in the
names, L/R directions, Latin-1 bytes, metric and imperial unit rows, back and side spin,
sentinels), each read to the SI values computed here by hand from the numbers in the file.
Exact unit factors: 1 mph = 0.44704 m/s, 1 km/h = 1/3.6 m/s, 1 yd = 0.9144 m, 1 ft = 0.3048 m,
1 rpm = 2 pi/60 rad/s; values compared to 1e-12 relative.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from mcrun.api import InputError
from mcrun.run.monitors import NAMES, read_session

DATA = Path(__file__).parent / "data" / "monitors"
MPH, KMH, YD, FT = 0.44704, 1.0 / 3.6, 0.9144, 0.3048
RPM, DEG = 2.0 * math.pi / 60.0, math.pi / 180.0
NAN = math.nan


def back_side(back, side):
    """(total spin rad/s, axis rad) from back and side spin in rpm: hypot and atan2."""
    return math.hypot(back, side) * RPM, math.atan2(side, back)


# The 7-iron and the driver of every file: (ball speed, launch, spin, axis, azimuth) and the
# device's (carry, total, apex, descent, carry side, total side), SI, NaN where not given.
IRON_MPH = (120.0 * MPH, 16.3 * DEG, 7097 * RPM, 2.5 * DEG, -1.2 * DEG)
DRIVER_MPH = (167.0 * MPH, 10.9 * DEG, 2686 * RPM, -3.0 * DEG, 0.5 * DEG)
IRON_DEVICE = (172.0 * YD, 180.5 * YD, 98.0 * FT, 50.0 * DEG, 3.1 * YD, 3.8 * YD)
DRIVER_DEVICE = (275.0 * YD, 295.2 * YD, 95.4 * FT, 38.1 * DEG, -10.2 * YD, -11.0 * YD)
SKY_IRON = back_side(7090, 310)
SKY_DRIVER = back_side(2682, -140)

CASES = {
    # file: (format, clubs, {quantity: [row values]})
    "trackman.csv": ("trackman", ["7 Iron", "Driver"], (IRON_MPH, DRIVER_MPH), None),
    "trackman-normalized.csv": (
        "trackman-normalized",
        ["7 Iron", "Driver"],
        (IRON_MPH, DRIVER_MPH),
        {"total": [181.0 * YD, 296.0 * YD], "total_side": [3.9 * YD, -11.4 * YD]},
    ),
    "garmin-r10-metric.csv": (
        "garmin-r10",
        ["7 Iron", "Driver"],
        (
            (193.1 * KMH, 16.3 * DEG, 6910 * RPM, 2.5 * DEG, -1.2 * DEG),
            (268.8 * KMH, 10.9 * DEG, 2684 * RPM, -9.2 * DEG, 0.5 * DEG),
        ),
        {
            "carry": [157.3, 251.5],
            "total": [164.0, 270.0],
            "apex": [27.4, 29.1],
            "carry_side": [2.8, -10.1],
            "total_side": [3.5, -10.8],
        },
    ),
    "garmin-r10-imperial.csv": (
        "garmin-r10",
        ["7 Iron"],
        (IRON_MPH,),
        {"carry": [172.0 * YD], "apex": [30.0 * YD], "total_side": [3.8 * YD]},
    ),
    "rapsodo-mlm2pro.csv": (
        "rapsodo-mlm2pro",
        ["7i", "Driver", "PW"],
        (
            (120.0 * MPH, 16.3 * DEG, 7097 * RPM, 2.5 * DEG, -1.2 * DEG),
            DRIVER_MPH,
            (102.0 * MPH, 24.2 * DEG, NAN, NAN, 0.0),
        ),
        {
            "carry": [172.0 * YD, 275.0 * YD, NAN],
            # Apex in feet (a real MLM2PRO export; read as yards it was 3x the flight's).
            "apex": [98.0 * FT, 95.4 * FT, NAN],
            "carry_side": [3.1 * YD, -10.2 * YD, NAN],
            "descent_angle": [50.0 * DEG, 38.1 * DEG, NAN],
        },
    ),
    "skytrak.csv": (
        "skytrak",
        ["7 Iron", "Driver"],
        (
            (120.0 * MPH, 16.3 * DEG, 7097 * RPM, SKY_IRON[1], -1.2 * DEG),
            # No total spin in the file: it follows from back and side spin.
            (167.0 * MPH, 10.9 * DEG, SKY_DRIVER[0], SKY_DRIVER[1], 0.5 * DEG),
        ),
        {"apex": [32.7 * YD, 31.8 * YD], "carry_side": [3.1 * YD, -10.2 * YD]},
    ),
    "flightscope-mevo.csv": (
        "flightscope-mevo",
        ["7 Iron", "Driver"],
        (
            (120.0 * MPH, 16.3 * DEG, 7097 * RPM, None, None),
            (167.0 * MPH, 10.9 * DEG, 2686 * RPM, None, None),
        ),
        {"carry": [172.0 * YD, 275.0 * YD], "apex": [98.0 * FT, 95.4 * FT]},
    ),
    "flightscope-mevo-plus.csv": (
        "flightscope-mevo-plus",
        ["7 Iron", "Driver"],
        (
            IRON_MPH,
            (167.0 * MPH, 10.9 * DEG, 2686 * RPM, 4.9 * DEG, -13.8 * DEG),
        ),
        {"carry_side": [3.1 * YD, 4.9 * YD], "descent_angle": [50.0 * DEG, 38.1 * DEG]},
    ),
    "foresight-fsx.csv": (
        "foresight-fsx",
        ["7 Iron", "Driver"],
        (
            (53.6, 16.3 * DEG, 7097 * RPM, back_side(7090, 310)[1], -1.2 * DEG),
            (74.7, 10.9 * DEG, 2686 * RPM, back_side(2682, -140)[1], 0.5 * DEG),
        ),
        # 16777215: the driver's descent angle was not measured.
        {"carry": [157.3, 251.5], "descent_angle": [50.0 * DEG, NAN], "carry_side": [2.8, -9.3]},
    ),
    "square-golf.csv": (
        "square-golf",
        ["7I", "DR"],
        (IRON_MPH, DRIVER_MPH),
        {"apex": [32.7 * YD, 31.8 * YD], "carry_side": [3.1 * YD, -10.2 * YD]},
    ),
    "awesome-golf.csv": (
        "awesome-golf",
        ["7 Iron", "Driver"],
        (IRON_MPH, DRIVER_MPH),
        {
            "carry": [172.0 * YD, 275.0 * YD],
            "apex": [98.0 * FT, 95.4 * FT],
            "carry_side": [3.1 * YD, -10.2 * YD],
            "total_side": [3.8 * YD, -11.0 * YD],
        },
    ),
    "gspro.jsonl": (
        "gspro",
        None,
        (
            (147.5 * MPH, 14.3 * DEG, 2250 * RPM, -13.2 * DEG, 2.3 * DEG),
            # Total spin and axis sent as 0: from back and side spin.
            (120.0 * MPH, 16.3 * DEG, *back_side(7090, 310), -1.2 * DEG),
        ),
        {"carry": [256.5 * YD, 157.3]},  # the second message in Meters
    ),
}
LAUNCH = ("ball_speed", "launch_angle", "spin", "spin_axis", "azimuth")


@pytest.mark.parametrize("name", sorted(CASES))
def test_each_format_reads_to_the_hand_computed_si_values(name):
    fmt, clubs, rows, device = CASES[name]
    session = read_session(DATA / name)
    assert session.format == fmt and session.detected
    assert (None if session.club is None else list(session.club)) == clubs
    for k, quantity in enumerate(LAUNCH):
        want = [row[k] for row in rows]
        if want[0] is None:
            assert quantity not in session.launch, quantity  # the format does not give it
            continue
        np.testing.assert_allclose(
            session.launch[quantity], want, rtol=1e-12, atol=0.0, err_msg=quantity
        )
    if device is None:
        device = dict(
            zip(
                ("carry", "total", "apex", "descent_angle", "carry_side", "total_side"),
                zip(IRON_DEVICE, DRIVER_DEVICE, strict=True),
                strict=True,
            )
        )
    for quantity, want in device.items():
        np.testing.assert_allclose(
            session.device[quantity], want, rtol=1e-12, atol=0.0, err_msg=quantity
        )


def test_every_format_has_a_fixture_and_forcing_it_reads_the_same():
    assert sorted({case[0] for case in CASES.values()} | {"mcrun"}) == sorted(NAMES)
    forced = read_session(DATA / "trackman.csv", format="trackman")
    assert not forced.detected
    np.testing.assert_array_equal(
        forced.launch["spin"], read_session(DATA / "trackman.csv").launch["spin"]
    )


def test_the_files_own_columns_are_kept_as_written():
    """Names as in the file (the Foresight spaces and trailing comma gone, the degree sign of
    Latin-1 read), values as written (an L/R direction stays text)."""
    foresight = read_session(DATA / "foresight-fsx.csv").frame
    assert list(foresight.columns[:3]) == ["Shot ID", "Club", "Club head Speed (m/s)"]
    assert foresight.columns[-1] == "Vert Impact (mm)" and foresight.shape == (2, 24)
    mevo = read_session(DATA / "flightscope-mevo.csv").frame
    assert "Launch Angle V (°)" in mevo.columns
    plus = read_session(DATA / "flightscope-mevo-plus.csv").frame
    assert list(plus["Launch H"]) == ["1.2 L", "13.8 L"]
    normalized = read_session(DATA / "trackman-normalized.csv").frame
    assert normalized["Spin Rate Type"].tolist() == ["Measured", "Estimated"]
    assert normalized["Carry Flat - Length (Sim)"].tolist() == [171.2, 276.3]


def test_unknown_blank_and_header_only_files_are_one_line(tmp_path):
    unknown = tmp_path / "unknown.csv"
    unknown.write_text("Shot,Speed (kph),Angle\n1,190,12\n", encoding="utf-8")
    blank = tmp_path / "blank.csv"
    blank.write_text("\n\n", encoding="utf-8")
    header_only = tmp_path / "header.csv"
    lines = (DATA / "trackman.csv").read_text(encoding="utf-8").splitlines()
    header_only.write_text("\n".join(lines[:2]) + "\n", encoding="utf-8")
    bad_unit = tmp_path / "bad-unit.csv"
    bad_unit.write_text("\n".join([lines[0], lines[1].replace("[mph]", "[furlong/h]"), lines[2]]))
    bad_json = tmp_path / "bad.jsonl"
    bad_json.write_text('{not json\n{"BallData": \n', encoding="utf-8")
    cases = [
        (blank, "no shots: the file is empty"),
        (header_only, "no shots: the file has a header only"),
        (bad_json, "no shots: line 1: not a JSON message"),
    ]
    for path, needle in cases:
        with pytest.raises(InputError) as info:
            read_session(path)
        message = str(info.value)
        assert "\n" not in message and message.startswith(f"{path}: "), message
        assert needle in message, message
    with pytest.raises(InputError) as info:
        read_session(unknown)
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{unknown}: ")
    assert "no recognisable column for ball_speed, launch_angle, spin" in message
    assert "found Shot, Speed (kph), Angle" in message
    assert all(name in message for name in NAMES), message
    with pytest.raises(InputError, match="column 'Ball Speed': unit 'furlong/h' is not a speed"):
        read_session(bad_unit)


# --- what real exports hold (issue 22) ------------------------------------------------------

SKYTRAK_HEADER = (DATA / "skytrak.csv").read_text(encoding="utf-8-sig").splitlines()[0]
SKYTRAK_IRON = (
    "1,7 Iron,Iron,2025-05-03 18:00:01,120.0,-1.2,16.3,7090,310,7097,172.0,180.5,3.1,32.7,50.0"
)


def skytrak(tmp_path, *rows, end="\n", name="s.csv"):
    """A SkyTrak export of the fixture's header and ``rows`` (each a line, or fields)."""
    path = tmp_path / name
    path.write_text("\n".join([SKYTRAK_HEADER, *rows]) + end, encoding="utf-8")
    return path


def test_a_cell_that_is_not_a_number_makes_its_shot_invalid_with_its_reason(tmp_path):
    """``--`` in a speed cell, ``T7091`` in a spin cell, a second unit row, a multi-line cell,
    a footer row: each row keeps its place with its reason; the good rows read as before."""
    fields = SKYTRAK_IRON.split(",")

    def row(k, value):
        return ",".join(fields[:k] + [value] + fields[k + 1 :])

    units = ",".join(
        ["", "", "", "", "[mph]", "[deg]", "[deg]", "[rpm]", "[rpm]", "[rpm]"] + [""] * 5
    )
    path = skytrak(
        tmp_path,
        SKYTRAK_IRON,
        row(4, "--"),
        row(7, "T7091").replace(",7097,", ",,"),
        units,
        row(4, '"120.\n5"'),
        "Average,,,,120.0,-1.2,16.3,7090,310,7097,172.0,180.5,3.1,32.7,50.0",
        SKYTRAK_IRON,
    )
    session = read_session(path)
    assert list(session.reasons) == [
        "",
        "Ball Speed (mph): '--' is not a number",
        "Back Spin (rpm): 'T7091' is not a number",
        "Ball Speed (mph): '[mph]' is not a number",
        "Ball Speed (mph): '120.\\n5' is not a number",
        "a summary row ('Average'), not a shot",
        "",
    ]
    speed = session.launch["ball_speed"]
    np.testing.assert_allclose(speed[[0, 6]], [120.0 * MPH] * 2, rtol=1e-12)
    assert np.isnan(speed[[1, 3, 4]]).all()


def test_square_golf_blank_and_prefixed_cells_read_as_the_vendor_means_them():
    """R2.5 right (+), L4.2 left (-); the impact columns H0.0/T9.3 (heel, toe) kept as text;
    the row with blank spin cells and a ``-`` spin axis has no spin (invalid when replayed),
    no crash."""
    session = read_session(DATA / "square-golf-blank-prefixed.csv")
    assert session.format == "square-golf"
    np.testing.assert_allclose(session.launch["azimuth"], [2.5 * DEG, -4.2 * DEG, 0.0], rtol=1e-12)
    np.testing.assert_allclose(session.launch["spin_axis"][:2], [-4.2 * DEG, 2.5 * DEG], rtol=1e-12)
    assert np.isnan(session.launch["spin"][2]) and np.isnan(session.launch["spin_axis"][2])
    assert session.reasons[2] == "Spin Axis: '-' is not a number"
    assert list(session.frame["ImpactHorizontal"][:2]) == ["H0.0", "T9.3"]
    assert list(session.frame["ImpactVertical"][:2]) == ["T9.3", "H0.0"]


def test_rapsodo_footer_rows_are_not_shots(tmp_path):
    lines = (DATA / "rapsodo-mlm2pro.csv").read_text(encoding="utf-8").splitlines()[:3]
    footer = '"Average","","","223.5","237.9","143.5","13.6","","97.1","","","","","4891",""'
    spread = '"Std. Dev.","","","51.5","57.4","23.5","2.7","","1.3","","","","","2205",""'
    path = tmp_path / "r.csv"
    path.write_text("\n".join([*lines, footer, spread]) + "\n", encoding="utf-8")
    session = read_session(path)
    assert list(session.reasons) == [
        "",
        "",
        "a summary row ('Average'), not a shot",
        "a summary row ('Std. Dev.'), not a shot",
    ]


def test_a_duplicated_column_takes_its_own_unit_or_is_refused(tmp_path):
    """Garmin's unit row under two Ball Speed columns, mph then km/h: each read in its own
    unit (they agree), the one in the app's unit read and a note says so. Without a unit row
    the km/h values under a second plain name disagree with the first: refused, one line."""
    header, units, row = (DATA / "garmin-r10-imperial.csv").read_text("utf-8-sig").splitlines()
    both = tmp_path / "both.csv"
    both.write_text(
        "\n".join([header + ",Ball Speed", units + ",[km/h]", row + ",193.1"]) + "\n", "utf-8"
    )
    session = read_session(both)
    assert session.launch["ball_speed"][0] == pytest.approx(120.0 * MPH, rel=1e-12)
    assert session.units["ball_speed"] == "mph" and session.sources["ball_speed"] == "Ball Speed"
    assert "ball_speed is in 2 columns that agree; read 'Ball Speed' (mph)" in session.notes[0]
    kmh_first = tmp_path / "kmh-first.csv"
    kmh_header = header.replace("Ball Speed", "Ball Speed (km/h)") + ",Ball Speed"
    kmh_units = units.replace("[mph],,[deg]", ",,[deg]", 1) + ",[mph]"  # the name says km/h
    kmh_row = row.replace(",120.0,", ",193.1,") + ",120.0"
    kmh_first.write_text("\n".join([kmh_header, kmh_units, kmh_row]) + "\n", "utf-8")
    session = read_session(kmh_first)  # the mph column read, whichever comes first
    assert session.sources["ball_speed"] == "Ball Speed"
    assert session.launch["ball_speed"][0] == pytest.approx(120.0 * MPH, rel=1e-12)
    plain = tmp_path / "plain.csv"
    plain.write_text("\n".join([header + ",Ball Speed", units + ",", row + ",193.1"]) + "\n")
    with pytest.raises(InputError) as info:
        read_session(plain)
    message = str(info.value)
    assert message.startswith(f"{plain}: columns 'Ball Speed' (mph) and 'Ball Speed.1' (mph)")
    assert "both give ball_speed and disagree (row 1: 53.6448 and 86.3234 in SI)" in message


def test_a_last_row_cut_mid_number_is_not_a_shot(tmp_path):
    """The file ends inside its last row (no line end, fewer fields than the rows before): a
    spin of 70 rpm is not a measurement. A complete last row without a line end reads."""
    cut = skytrak(tmp_path, SKYTRAK_IRON, SKYTRAK_IRON[: SKYTRAK_IRON.index("7090") + 2], end="")
    session = read_session(cut)
    assert list(session.reasons) == ["", "the last row is cut short (8 of 15 fields, no line end)"]
    whole = skytrak(tmp_path, SKYTRAK_IRON, SKYTRAK_IRON, end="", name="whole.csv")
    assert list(read_session(whole).reasons) == ["", ""]


def test_a_byte_order_mark_encoded_twice_is_dropped():
    session = read_session(DATA / "skytrak-double-bom.csv")
    assert session.format == "skytrak" and session.detected
    assert session.frame.columns[0] == "Shot Number"
    np.testing.assert_array_equal(
        session.launch["spin"], read_session(DATA / "skytrak.csv").launch["spin"]
    )


def test_binary_garbage_and_a_huge_header_are_one_short_line(tmp_path):
    rng = np.random.default_rng(22)
    nuls = tmp_path / "nuls.csv"
    nuls.write_bytes(b"\x00" * 5400 + b"\n1,2\n")
    noise = tmp_path / "noise.csv"
    noise.write_bytes(rng.integers(0, 256, 20_000, dtype=np.uint8).tobytes().replace(b"\x00", b"x"))
    wide = tmp_path / "wide.csv"
    wide.write_text(",".join(f"c{k}" for k in range(20_000)) + "\n" + ",".join(["1"] * 20_000))
    for path in (nuls, noise, wide):
        with pytest.raises(InputError) as info:
            read_session(path)
        message = str(info.value)
        assert message.startswith(f"{path}: ") and "\n" not in message, message[:300]
        assert len(message) < 600 and "\x00" not in message, message[:300]
    assert "not a text file" in str(pytest.raises(InputError, read_session, nuls).value)
    with pytest.raises(InputError, match=r"found c0, c1, .*, c11 and 19988 more; or an export"):
        read_session(wide)


@pytest.mark.parametrize("name", ["skytrak.csv", "trackman.csv", "garmin-r10-imperial.csv"])
def test_an_export_with_lines_ended_by_cr_alone_reads_as_with_crlf(tmp_path, name):
    """Excel for Mac's "CSV (Macintosh)" ends its lines with CR alone: read as the same rows and
    launches as the export with CRLF (a csv module error about universal-newline mode
    before)."""
    text = (DATA / name).read_bytes().decode("utf-8").replace("\r\n", "\n")
    paths = {}
    for end in ("\r", "\r\n"):
        paths[end] = tmp_path / f"{len(end)}-{name}"
        paths[end].write_bytes(text.replace("\n", end).encode("utf-8"))
    cr, crlf = (read_session(paths[end]) for end in ("\r", "\r\n"))
    assert cr.format == crlf.format and len(cr.frame) == len(crlf.frame) > 0
    for column in cr.frame.columns:
        assert cr.frame[column].equals(crlf.frame[column]), column


def _resaved(text, sep, decimal, grouped=False, sep_line=False):
    """An export's text as Excel saves it in another locale: fields separated by ``sep``,
    decimals written with ``decimal``; with ``grouped``, thousands grouped by the other mark
    (``7.097`` where the decimal mark is a comma, ``7,097`` where it is a point); with
    ``sep_line``, a ``sep=`` line first."""
    import csv
    import io
    import re

    number = re.compile(r"^(\s*[LR]?\s*[+-]?)(\d+)(?:\.(\d+))?(\s*[LR]?\s*)$", re.IGNORECASE)
    group = "." if decimal == "," else ","

    def written(field):
        found = number.match(field)
        if found is None:
            return field
        side, whole, decimals, end = found.groups()
        if grouped and len(whole) > 3 and whole[0] != "0":
            whole = f"{int(whole):,}".replace(",", group)
        return f"{side}{whole}{decimal + decimals if decimals else ''}{end}"

    out = io.StringIO()
    if sep_line and not text.startswith("sep="):
        out.write(f"sep={sep}\r\n")
    writer = csv.writer(out, delimiter=sep, lineterminator="\r\n")
    for line in text.splitlines():
        if line.startswith("sep="):
            out.write(f"sep={sep}\r\n")
            continue
        fields = next(csv.reader([line]), [])
        writer.writerow([written(f) for f in fields])
    return out.getvalue()


CSV_FIXTURES = sorted(p.name for p in DATA.glob("*.csv"))


@pytest.mark.parametrize("name", CSV_FIXTURES)
def test_an_export_saved_with_semicolons_tabs_or_decimal_commas_reads_the_same(tmp_path, name):
    """Excel saves a CSV with ';' between the fields and decimal commas where the decimal mark
    is a comma (most of Europe), and "Unicode Text" as UTF-16 with tabs, thousands grouped
    where the cells are formatted so (``7.097`` or ``7,097`` rpm; ``"7,097"`` quoted in a
    comma-separated file, as Excel saves it where the decimal mark is a point): each read as
    the same launches and device results as the export itself, its columns of numbers numbers
    (refused as a file of no known columns before; and 7.097 rpm, or 7.097 for ``7,097`` in
    a file of decimal points, before the thousands were read)."""
    data = (DATA / name).read_bytes()
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
    original = read_session(DATA / name)
    saved = {
        "semicolon": ("utf-8", _resaved(text, ";", ",", grouped=True)),
        "unicode-text": ("utf-16", _resaved(text, "\t", ",")),
        "tab": ("utf-8", _resaved(text, "\t", ".", grouped=True)),
        "semicolon sep= line": ("utf-8-sig", _resaved(text, ";", ",", sep_line=True)),
        "commas, thousands quoted": ("utf-8", _resaved(text, ",", ".", grouped=True)),
        # Google Sheets where the decimal mark is a comma: commas between the fields, the
        # decimals quoted ("45,3"), thousands grouped by points (7.097, which pandas read as
        # 7.097)
        "commas, decimal commas quoted": ("utf-8", _resaved(text, ",", ",", grouped=True)),
    }
    for how, (encoding, body) in saved.items():
        path = tmp_path / f"{how}-{name}"
        path.write_bytes(body.encode(encoding))
        session = read_session(path)
        assert session.format == original.format and len(session.frame) == len(original.frame)
        for part in ("launch", "device"):
            ours, theirs = getattr(session, part), getattr(original, part)
            assert ours.keys() == theirs.keys(), (how, part)
            for quantity in theirs:
                np.testing.assert_array_equal(ours[quantity], theirs[quantity], err_msg=how)
        assert list(session.reasons != "") == list(original.reasons != ""), how
        for column in original.frame.columns:  # (the file's own columns, as written)
            kind = original.frame[column].dtype.kind
            assert session.frame[column].dtype.kind == kind or kind not in "fi", (how, column)
        if not how.startswith("commas"):
            said = f"fields separated by {'tabs' if 'semicolon' not in how else repr(';')}"
            assert any(said in note for note in session.notes), session.notes
        if how == "commas, decimal commas quoted":
            said = "fields separated by ','; numbers with a decimal comma"
            assert any(said in note for note in session.notes), session.notes


def test_gspro_messages_are_read_out_of_a_connectors_log():
    """Prefixes and arrows before each message, other log lines between, heartbeats and
    GSPro's replies skipped, a message logged with Python's repr (``Backspin``, TotalSpin 0:
    from back and side spin), one spread over lines, and the last one cut short (its row kept,
    with its reason)."""
    session = read_session(DATA / "gspro-connector.log")
    assert session.format == "gspro" and session.detected
    assert list(session.frame["ShotNumber"][:3]) == [1, 2, 3]
    launch = session.launch
    np.testing.assert_allclose(
        launch["ball_speed"][:3], [147.5 * MPH, 120.0 * MPH, 102.0 * MPH], rtol=1e-12
    )
    np.testing.assert_allclose(
        [launch["spin"][1], launch["spin_axis"][1]], back_side(7090, 310), rtol=1e-12
    )
    np.testing.assert_allclose(launch["spin"][[0, 2]], [2250 * RPM, 9304 * RPM], rtol=1e-12)
    np.testing.assert_allclose(session.device["carry"][:2], [256.5 * YD, 157.3], rtol=1e-12)
    assert list(session.reasons[:3]) == ["", "", ""]
    assert session.reasons[3].startswith("line 14: not a JSON message")
    assert "4 message(s) without ball data skipped" in session.notes[0]


@pytest.mark.parametrize(
    ("rows", "want"),
    [
        # mcrun's own columns saved with semicolons (refused before: "row 1 has 3 fields").
        ("150,5;12,5;2.686;1,5", (150.5, 12.5, 2686.0, 1.5)),
        # A group of thousands never starts with 0: -0,025 is a decimal (read as -25 before).
        ("150;12;2686;-0,025", (150.0, 12.0, 2686.0, -0.025)),
        # Only three-decimal cells, as many with a point as with a comma: ';' is Excel's
        # separator where the decimal mark is a comma (150250 mph before).
        ("150,250;12,500;2686;1,380", (150.25, 12.5, 2686.0, 1.38)),
    ],
)
def test_a_spreadsheet_s_numbers_are_read_as_its_locale_writes_them(tmp_path, rows, want):
    path = tmp_path / "own.csv"
    path.write_text(f"ball_speed_mph;launch_deg;spin_rpm;azimuth_deg\n{rows}\n")
    session = read_session(path)
    mph, deg, rpm = 0.44704, math.pi / 180.0, math.pi / 30.0
    got = [session.launch[q][0] for q in ("ball_speed", "launch_angle", "spin", "azimuth")]
    wanted = [want[0] * mph, want[1] * deg, want[2] * rpm, want[3] * deg]
    assert got == pytest.approx(wanted, rel=1e-12)
    assert "fields separated by ';'; numbers with a decimal comma" in session.notes[0]


def test_a_device_result_no_shot_can_have_is_not_measured(tmp_path):
    """A carry of -1,234.5 yd (a cell the device or a spreadsheet got wrong) is read as not
    measured, with a note: it made the model's bias +1,348 m."""
    text = (DATA / "skytrak.csv").read_text(encoding="utf-8-sig")
    path = tmp_path / "odd.csv"
    path.write_text(text.replace(",172.0,180.5,", ",-1234.5,180.5,", 1))
    session = read_session(path)
    carry = session.device["carry"]
    assert math.isnan(carry[0]) and carry[1] == pytest.approx(275.0 * 0.9144)
    assert session.device["total"][0] == pytest.approx(180.5 * 0.9144)  # (the row's others)
    assert any(
        "1 value(s) of Carry (yds) no shot can have (row 1: '-1234.5' yd), read as not " in note
        for note in session.notes
    ), session.notes


def test_mcrun_s_own_columns_read_quoted_thousands_and_refuse_infinite_results(tmp_path):
    """mcrun's own columns: a quoted "2,855" rpm is 2855, as in an export (refused before);
    an infinite device result, or a carry of 0 (what devices write for none), is not
    measured (inf reached the Parquet and a bias of -inf)."""
    path = tmp_path / "own.csv"
    path.write_text(
        "ball_speed_mph,launch_deg,spin_rpm,carry_yd,total_yd\n"
        '151.0,13.4,"2,855",inf,0\n'
        "150.0,12.9,2884,248.1,1e400\n"
    )
    session = read_session(path)
    assert session.launch["spin"][0] == pytest.approx(2855 * math.pi / 30.0, rel=1e-12)
    carry, total = session.device["carry"], session.device["total"]
    assert math.isnan(carry[0]) and carry[1] == pytest.approx(248.1 * 0.9144)
    assert np.isnan(total).all()
    assert any("2 value(s) of total_yd no shot can have" in note for note in session.notes)


@pytest.mark.parametrize(
    ("encoding", "sep_line"),
    [
        ("utf-16", False),
        ("utf-16-le", False),
        ("utf-16-be", False),
        ("utf-8", True),
        ("utf-16", True),
    ],
)
def test_mcrun_s_own_columns_read_in_utf_16_and_after_a_sep_line(tmp_path, encoding, sep_line):
    """mcrun's own columns, comma-separated, as UTF-16 with its byte-order mark (a UTF-8 error
    before, though an export in UTF-16 was read) and after a spreadsheet's ``sep=,`` line
    ("row 1 has 3 fields, the header has 2"): the same launches as the file in UTF-8."""
    text = "ball_speed_mph,launch_deg,spin_rpm\n151,13.4,2855\n150.5,12.9,2884\n"
    plain = tmp_path / "plain.csv"
    plain.write_text(text, encoding="utf-8")
    path = tmp_path / "saved.csv"
    body = ("sep=,\n" if sep_line else "") + text
    mark = "\ufeff" if encoding in ("utf-16-le", "utf-16-be") else ""  # ("utf-16" writes it)
    path.write_bytes((mark + body).encode(encoding))
    want = read_session(plain).launch
    for got in (read_session(path).launch, read_session(path, format="mcrun").launch):
        assert want.keys() == got.keys()
        for quantity in want:
            np.testing.assert_array_equal(got[quantity], want[quantity], err_msg=quantity)
