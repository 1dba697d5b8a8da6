#!/usr/bin/env python3
"""Compare two somasim run folders (the outputs of `somasim run ... --out DIR`).

Usage:
    tools/compare_runs.py DIR_A DIR_B [--rel-tol 0] [--abs-tol 0] [-v]

Written to check that a change which must not alter behaviour (e.g. restructuring the source
tree) leaves every output of every experiment unchanged; tools/check_behaviour_unchanged.sh runs
the shipped configs with two builds and calls this on each pair of run folders.

What is compared (all files under both folders, recursively):
  * the set of files must be equal, except for the files that legitimately differ between two
    runs or two source trees and are ignored: log.txt (time stamps, paths) and
    experiment.resolved.yaml (absolute paths; a newer revision may add sections);
  * metrics.json: parsed as JSON and compared as a tree. Ignored, at any depth, are the keys
    whose values depend on the wall clock or on the build rather than on the simulation:
    `wall_time_s`, `real_time_factor` (sim_time_s / wall_time_s), `versions` (version strings,
    compiler), any key whose name contains "wall", and any key ending in "_ms" (plugins' own
    wall-clock timings, e.g. body_schema_filter's filter_step_ms). Everything else (status, error,
    stop_reason, seed, sim_time_s and every plugin metric) must match: numbers with the
    tolerance below, and with --rel-tol 0 exactly (same value and same JSON type, int vs float).
    Why these keys: core/framework/src/runner.cpp reads the clock for wall_time_s (and
    real_time_factor derived from it), plugins time their own stages in *_ms metrics, and
    `versions` names the build, not the behaviour; two
    runs of the same config with the same build differ in metrics.json in exactly these keys;
  * *.png: byte for byte. When the bytes differ the images are decoded (IHDR/PLTE/IDAT, zlib);
    if the pixels (and size, colour type, palette) are identical the difference can only be
    metadata or compression (e.g. another libpng/zlib), which is reported as a TOL line and
    counted "within tolerance", never as a difference;
  * every other file that is text (CSVs, learned maps in JSON, ...): line by line. Equal lines
    are fine; where lines differ, the fields (CSV: comma-separated cells; other text: numbers
    and the text between them) are compared: text exactly, numbers with the tolerance.
    With --rel-tol 0 (the default) any textual difference is a difference ("bit for bit":
    the programs print doubles with round-trip precision);
  * any other (binary) file: byte for byte.

Tolerance: two numbers a, b match if a == b, or |a - b| <= rel_tol * max(|a|, |b|) + abs_tol.
NaN matches NaN; infinities must be equal.

Columns in messages: for CSV files the field number (and its header); for other text files
the character position where the differing token starts; for metrics.json the JSON path.

Output: one line per file that is not identical (DIFFER / TOL / ONLY-IN-A / ONLY-IN-B) with
the first difference (file, line, column, the two values; -v also lists identical files as
SAME), then the summary line
    N files identical, M within tolerance, K differ
Exit status: 0 if no file differs beyond tolerance, 1 if some do, 2 on usage errors.
"""

import argparse
import json
import math
import os
import re
import struct
import sys
import zlib

IGNORED_FILES = {"log.txt", "experiment.resolved.yaml"}
IGNORED_METRIC_KEYS = {"wall_time_s", "real_time_factor", "versions"}

# A number as the programs print them (C++ streams, fmt, nlohmann::json), or nan/inf.
NUMBER = r"[-+]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|(?:nan|inf(?:inity)?)(?![A-Za-z_]))"
NUMBER_FULL = re.compile(r"\s*(" + NUMBER + r")\s*\Z", re.IGNORECASE)
NUMBER_ANY = re.compile(NUMBER, re.IGNORECASE)


IDENTICAL, WITHIN, DIFFER = "identical", "within", "differ"


class Tol:
    def __init__(self, rel, abs_):
        self.rel = rel
        self.abs = abs_
        self.max_rel_seen = 0.0  # largest relative difference accepted
        self.max_abs_seen = 0.0

    @property
    def exact(self):
        return self.rel == 0 and self.abs == 0

    def numbers_match(self, a, b):
        """a, b: Python numbers (int or float)."""
        if isinstance(a, int) and isinstance(b, int):
            if a == b:
                return True
            fa, fb = float(a), float(b)
        else:
            fa, fb = float(a), float(b)
        if fa == fb:
            return True
        if math.isnan(fa) and math.isnan(fb):
            return True
        if math.isnan(fa) or math.isnan(fb) or math.isinf(fa) or math.isinf(fb):
            return False
        diff = abs(fa - fb)
        scale = max(abs(fa), abs(fb))
        if diff <= self.rel * scale + self.abs:
            if scale > 0:
                self.max_rel_seen = max(self.max_rel_seen, diff / scale)
            self.max_abs_seen = max(self.max_abs_seen, diff)
            return True
        return False


def parse_number(text):
    """Number in text as int or float, or None if text is not (only) a number."""
    m = NUMBER_FULL.match(text)
    if not m:
        return None
    s = m.group(1)
    if re.fullmatch(r"[-+]?\d+", s):
        return int(s)
    return float(s)


def short(s, n=60):
    s = s if isinstance(s, str) else repr(s)
    return s if len(s) <= n else s[: n - 3] + "..."


def rel_diff(a, b):
    try:
        fa, fb = float(a), float(b)
        scale = max(abs(fa), abs(fb))
        return abs(fa - fb) / scale if scale > 0 else 0.0
    except (TypeError, ValueError, OverflowError):
        return float("nan")


# ---------------------------------------------------------------------------------------------
# Text files (CSV and everything else that decodes as text)


def tokens(line):
    """Split a non-CSV line into ('text', s) and ('num', s) pieces, with start columns."""
    out = []
    pos = 0
    for m in NUMBER_ANY.finditer(line):
        # A digit run inside an identifier (taxel_12, v2) is text, not a number.
        if m.start() > 0 and (line[m.start() - 1].isalnum() or line[m.start() - 1] == "_"):
            continue
        if m.start() > pos:
            out.append(("text", line[pos:m.start()], pos))
        out.append(("num", m.group(0), m.start()))
        pos = m.end()
    if pos < len(line):
        out.append(("text", line[pos:], pos))
    return out


def compare_csv_line(la, lb, header, tol):
    """None if the lines match within tolerance, else (column, name, value_a, value_b)."""
    fa, fb = la.split(","), lb.split(",")
    if len(fa) != len(fb):
        return (min(len(fa), len(fb)) + 1, "field count", "%d fields" % len(fa),
                "%d fields" % len(fb))
    for i, (x, y) in enumerate(zip(fa, fb)):
        if x == y:
            continue
        name = header[i] if header and i < len(header) else ""
        if tol.exact:
            return (i + 1, name, x, y)
        nx, ny = parse_number(x), parse_number(y)
        if nx is None or ny is None or not tol.numbers_match(nx, ny):
            return (i + 1, name, x, y)
    return None


def compare_text_line(la, lb, tol):
    """None if the lines match within tolerance, else (column, '', value_a, value_b)."""
    if tol.exact:
        col = next((i for i, (x, y) in enumerate(zip(la, lb)) if x != y), min(len(la), len(lb)))
        # widen to the whole token around the first differing character
        stop = ",:[]{}\""
        lo = col
        while lo > 0 and not la[lo - 1].isspace() and la[lo - 1] not in stop:
            lo -= 1

        def token_from(s):
            hi = lo
            while hi < len(s) and not s[hi].isspace() and s[hi] not in stop:
                hi += 1
            return s[lo:hi] if hi > lo else s[lo:lo + 1]
        return (lo + 1, "", token_from(la), token_from(lb))
    ta, tb = tokens(la), tokens(lb)
    if len(ta) != len(tb) or any(x[0] != y[0] for x, y in zip(ta, tb)):
        col = next((x[2] for x, y in zip(ta, tb) if x[:2] != y[:2]), min(len(la), len(lb)))
        return (col + 1, "", short(la[col:]), short(lb[col:]))
    for (kind, x, col), (_, y, _) in zip(ta, tb):
        if x == y:
            continue
        if kind == "text":
            return (col + 1, "", x, y)
        nx, ny = parse_number(x), parse_number(y)
        if nx is None or ny is None or not tol.numbers_match(nx, ny):
            return (col + 1, "", x, y)
    return None


def compare_text(name, a_text, b_text, tol):
    # a final newline ends the last line; it does not start an empty one
    ends_a, ends_b = a_text.endswith("\n"), b_text.endswith("\n")
    la = (a_text[:-1] if ends_a else a_text).split("\n")
    lb = (b_text[:-1] if ends_b else b_text).split("\n")
    is_csv = name.endswith(".csv")
    header = la[0].split(",") if is_csv and la else None
    status = IDENTICAL
    for i, (x, y) in enumerate(zip(la, lb)):
        if x == y:
            continue
        d = (compare_csv_line(x, y, header, tol) if is_csv and i > 0
             else compare_text_line(x, y, tol))
        if d is not None:
            col, colname, va, vb = d
            where = "line %d, column %d%s" % (i + 1, col, " (%s)" % colname if colname else "")
            extra = ""
            na, nb = parse_number(str(va)), parse_number(str(vb))
            if na is not None and nb is not None:
                extra = "  (rel diff %.3g)" % rel_diff(na, nb)
            return DIFFER, "%s: A=%s B=%s%s" % (where, short(va), short(vb), extra)
        status = WITHIN
    if len(la) != len(lb):
        n = min(len(la), len(lb))
        longer = "A" if len(la) > len(lb) else "B"
        extra = (la if len(la) > len(lb) else lb)[n]
        return DIFFER, "line %d: %d vs %d lines; first extra line (in %s): %s" % (
            n + 1, len(la), len(lb), longer, short(extra, 100))
    if ends_a != ends_b:
        return DIFFER, "line %d: final newline only in %s" % (len(la), "A" if ends_a else "B")
    return status, None


# ---------------------------------------------------------------------------------------------
# metrics.json


def metric_key_ignored(key):
    return key in IGNORED_METRIC_KEYS or "wall" in key or key.endswith("_ms")


def compare_json(a, b, path, tol):
    """None if equal within tolerance, else a description of the first difference."""
    if isinstance(a, dict) and isinstance(b, dict):
        ka = {k for k in a if not metric_key_ignored(k)}
        kb = {k for k in b if not metric_key_ignored(k)}
        if ka != kb:
            only_a, only_b = sorted(ka - kb), sorted(kb - ka)
            return "%s: keys only in A %s, only in B %s" % (path or "/", only_a[:5], only_b[:5])
        for k in sorted(ka):
            d = compare_json(a[k], b[k], "%s/%s" % (path, k), tol)
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return "%s: list length %d vs %d" % (path, len(a), len(b))
        for i, (x, y) in enumerate(zip(a, b)):
            d = compare_json(x, y, "%s[%d]" % (path, i), tol)
            if d:
                return d
        return None
    num = (int, float)
    if (isinstance(a, num) and not isinstance(a, bool) and isinstance(b, num)
            and not isinstance(b, bool)):
        if tol.exact:
            # bit for bit: same value and same JSON type (1 vs 1.0 prints differently)
            same = type(a) is type(b) and (
                (a == b and math.copysign(1, a) == math.copysign(1, b)) or (a != a and b != b))
        else:
            same = tol.numbers_match(a, b)
        if same:
            return None
        if a == b:
            return "%s: A=%r B=%r  (same value, printed differently: int vs float or sign of 0)" % (
                path, a, b)
        return "%s: A=%r B=%r  (rel diff %.3g)" % (path, a, b, rel_diff(a, b))
    if type(a) is not type(b) or a != b:
        return "%s: A=%s B=%s" % (path, short(json.dumps(a)), short(json.dumps(b)))
    return None


def compare_metrics(a_bytes, b_bytes, tol):
    try:
        a = json.loads(a_bytes.decode("utf-8"))
        b = json.loads(b_bytes.decode("utf-8"))
    except (ValueError, UnicodeDecodeError) as e:
        return DIFFER, "cannot parse as JSON: %s" % e
    exact = Tol(0, 0)
    if compare_json(a, b, "", exact) is None:
        return IDENTICAL, None
    d = compare_json(a, b, "", tol)
    if d is None:
        return WITHIN, None
    return DIFFER, d


# ---------------------------------------------------------------------------------------------
# PNG


def png_pixels(data):
    """(IHDR fields, PLTE, tRNS, decoded rows) of a PNG, or raises ValueError."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, ihdr, plte, trns, idat = 8, None, None, None, []
    while pos + 8 <= len(data):
        length, ctype = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if ctype == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif ctype == b"PLTE":
            plte = body
        elif ctype == b"tRNS":
            trns = body
        elif ctype == b"IDAT":
            idat.append(body)
        elif ctype == b"IEND":
            break
    if ihdr is None:
        raise ValueError("no IHDR")
    width, height, depth, colour, _, _, interlace = ihdr
    raw = zlib.decompress(b"".join(idat))
    if interlace != 0:
        return ihdr, plte, trns, raw  # not unfiltered; compared as filtered data
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[colour]
    bpp = max(1, channels * depth // 8)
    stride = (width * channels * depth + 7) // 8
    rows, prev = [], bytearray(stride)
    p = 0
    for _ in range(height):
        ftype = raw[p]
        line = bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        if ftype == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 0xFF
        elif ftype == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 0xFF
        elif ftype == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 0xFF
        elif ftype == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                pr = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                line[i] = (line[i] + pr) & 0xFF
        elif ftype != 0:
            raise ValueError("bad filter type %d" % ftype)
        rows.append(bytes(line))
        prev = line
    return ihdr, plte, trns, rows


def compare_png(a, b):
    if a == b:
        return IDENTICAL, None
    try:
        ha, pa, ta, ra = png_pixels(a)
        hb, pb, tb, rb = png_pixels(b)
    except (ValueError, zlib.error, struct.error, KeyError, IndexError) as e:
        return DIFFER, "bytes differ and cannot be decoded (%s)" % e
    if ha != hb:
        return DIFFER, "image header differs: A %dx%d depth %d colour %d, B %dx%d depth %d colour %d" % (
            ha[0], ha[1], ha[2], ha[3], hb[0], hb[1], hb[2], hb[3])
    if pa != pb or ta != tb:
        return DIFFER, "palette or transparency differs"
    if ra == rb:
        return "png-same", "bytes differ (%d vs %d bytes) but the pixels are identical: metadata or compression only" % (len(a), len(b))
    if isinstance(ra, bytes):
        return DIFFER, "pixel data differ (interlaced image)"
    width = ha[0]
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[ha[3]]
    nbytes = max(1, channels * ha[2] // 8)
    ndiff = 0
    first = None
    for y, (x1, x2) in enumerate(zip(ra, rb)):
        if x1 != x2:
            cols = [i for i in range(len(x1)) if x1[i] != x2[i]]
            ndiff += len(cols)
            if first is None:
                i = cols[0]
                first = (y, i // nbytes if ha[2] >= 8 else i, x1[i], x2[i])
    y, x, va, vb = first
    return DIFFER, "pixels differ: first at x=%d y=%d (byte A=%d B=%d), %d of %d bytes differ" % (
        x, y, va, vb, ndiff, sum(len(r) for r in ra))


# ---------------------------------------------------------------------------------------------


def list_files(root):
    out = set()
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        for f in filenames:
            rel = os.path.relpath(os.path.join(dirpath, f), root)
            if os.path.basename(rel) in IGNORED_FILES and os.path.dirname(rel) == "":
                continue
            out.add(rel)
    return out


def as_text(data):
    if b"\0" in data:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None


def compare_file(rel, a, b, tol):
    name = os.path.basename(rel)
    if rel == "metrics.json":
        return compare_metrics(a, b, tol)
    if name.lower().endswith(".png"):
        return compare_png(a, b)
    if a == b:
        return IDENTICAL, None
    ta, tb = as_text(a), as_text(b)
    if ta is None or tb is None:
        i = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
        return DIFFER, "binary files differ at byte %d (sizes %d vs %d)" % (i, len(a), len(b))
    return compare_text(name, ta, tb, tol)


def main(argv=None):
    p = argparse.ArgumentParser(
        description="Compare two somasim run folders (see the module docstring).")
    p.add_argument("dir_a")
    p.add_argument("dir_b")
    p.add_argument("--rel-tol", type=float, default=0.0,
                   help="relative tolerance for numbers (default 0: exact text)")
    p.add_argument("--abs-tol", type=float, default=0.0,
                   help="absolute tolerance added to the relative one (default 0), for values "
                        "that should be 0 but come out as 1e-17 after a reordered sum")
    p.add_argument("-v", "--verbose", action="store_true", help="also list identical files")
    args = p.parse_args(argv)
    for d in (args.dir_a, args.dir_b):
        if not os.path.isdir(d):
            print("compare_runs: not a directory: %s" % d, file=sys.stderr)
            return 2
    if args.rel_tol < 0 or args.abs_tol < 0 or math.isnan(args.rel_tol) or math.isnan(args.abs_tol):
        print("compare_runs: tolerances must be >= 0", file=sys.stderr)
        return 2

    fa, fb = list_files(args.dir_a), list_files(args.dir_b)
    n_same = n_within = n_differ = 0
    for rel in sorted(fa | fb):
        if rel not in fb:
            print("ONLY-IN-A  %s" % rel)
            n_differ += 1
            continue
        if rel not in fa:
            print("ONLY-IN-B  %s" % rel)
            n_differ += 1
            continue
        with open(os.path.join(args.dir_a, rel), "rb") as f:
            a = f.read()
        with open(os.path.join(args.dir_b, rel), "rb") as f:
            b = f.read()
        tol = Tol(args.rel_tol, args.abs_tol)
        status, detail = compare_file(rel, a, b, tol)
        if status == IDENTICAL:
            n_same += 1
            if args.verbose:
                print("SAME       %s" % rel)
        elif status == "png-same":
            n_within += 1
            print("TOL        %s: %s" % (rel, detail))
        elif status == WITHIN:
            n_within += 1
            print("TOL        %s: within tolerance (largest relative difference %.3g, "
                  "absolute %.3g)" % (rel, tol.max_rel_seen, tol.max_abs_seen))
        else:
            n_differ += 1
            print("DIFFER     %s: %s" % (rel, detail))
    print("%d files identical, %d within tolerance, %d differ" % (n_same, n_within, n_differ))
    return 1 if n_differ else 0


if __name__ == "__main__":
    sys.exit(main())
