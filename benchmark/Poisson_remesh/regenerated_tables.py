#!/usr/bin/env python3
"""regenerated_tables.py GENERATED_DIR PICTURES_DIR FILE... -- rewrites the tables that README.md
and RESULTS.md quote from the benchmark's generated files, so that no quoted table is edited by
hand (run by benchmark/run_all.sh after the tables are made).

In each FILE, the lines between a marker `<!-- table: NAME -->` and the next `<!-- /table -->`
are replaced by table NAME, built from the files of GENERATED_DIR (or PICTURES_DIR):
  corpus_summary   the summary rows of corpus_results.md and corpus_results_unconstrained_peer.md
  eight_models     remesh_results.json: ours beside CGAL on each model
  pictures         the quality tables the program printed beside each picture (PICTURES_DIR/*.txt)
A table whose files are missing is left as it is, and said on stderr.
"""
import json
import os
import re
import sys


def markdown_rows(path):
    """{header: value} for each row of the first table whose header has 'floor holds'"""
    rows, header = [], None
    with open(path, encoding="utf-8") as f:
        for line in f:
            if not line.startswith("|"):
                if header and rows:
                    break
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if header is None:
                if "floor holds" in cells:
                    header = cells
                continue
            if set(line.strip()) <= set("|-: "):
                continue
            rows.append(dict(zip(header, cells)))
    return rows


def corpus_summary(gen, _pictures):
    runs = [("corpus_results.md", "peer's sharp edges constrained"),
            ("corpus_results_unconstrained_peer.md", "peer's sharp edges free")]
    out = ["| run | contender | floor holds | θmin (°) median / worst | θmin away (°) median / worst | θ̄min (°) median / worst "
           "| irregular (%) median / worst | RMS (% diag) median / worst | Hausdorff (% diag) median / worst "
           "| time / CGAL's: median / 90th pct. / max |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for name, label in runs:
        path = os.path.join(gen, name)
        if not os.path.exists(path):
            raise FileNotFoundError(path)
        commit = ""
        with open(path, encoding="utf-8") as f:
            for line in f:
                m = re.match(r"Commit (\w+)", line)
                if m:
                    commit = m.group(1)
                    break
        for i, r in enumerate(markdown_rows(path)):
            who = {"ours": "ours", "cgal": "CGAL"}.get(r.get("contender", ""), r.get("contender", ""))
            out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                "%s (%s)" % (label, commit) if i == 0 else "", who, r.get("floor holds", ""),
                r.get("θmin (°) median / worst", ""), r.get("θmin away (°) median / worst", ""),
                r.get("θ̄min (°) median / worst", ""), r.get("irregular (%) median / worst", ""),
                r.get("RMS (% diag) median / worst", ""), r.get("Hausdorff (% diag) median / worst", ""),
                r.get("time / CGAL's: median / 90th pct. / max", "")))
    return out


def eight_models(gen, _pictures):
    path = os.path.join(gen, "remesh_results.json")
    with open(path, encoding="utf-8") as f:
        rows = json.load(f)["rows"]
    by = {}
    order = []
    for r in rows:
        if r["mesh"] not in by:
            order.append(r["mesh"])
        by.setdefault(r["mesh"], {})[r["contender"]] = r
    out = ["| mesh | contender | V | θmin (°) | θ̄min (°) | <30° (%) | irregular (%) | RMS (% diag) | Hausdorff (% diag) "
           "| crossings (away from the input's own) | seconds |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for mesh in order:
        for contender, shown in (("poisson_remesh", "ours"), ("cgal_isotropic", "CGAL")):
            r = by[mesh].get(contender)
            if r is None:
                continue
            if not r.get("ok", False):
                out.append("| %s | %s | failed: %s ||||||||" % (mesh if shown == "ours" else "", shown, r.get("error", "")))
                continue
            theta = "%.2f" % r["min_angle_deg"]
            away = r["min_angle_away_from_sharp_corners_deg"]
            if abs(away - r["min_angle_deg"]) > 0.005:
                theta += " (%.2f away from corners and tips)" % away
            out.append("| %s | %s | %d | %s | %.2f | %.2f | %.1f | %.4f | %.3f | %d (%d) | %.3f |" % (
                mesh if shown == "ours" else "", shown, r["vertices"], theta, r["mean_min_angle_deg"],
                100 * r["share_min_angle_below_30"], 100 * r["irregular_share"], 100 * r["rms_over_diagonal"],
                100 * r["hausdorff_over_diagonal"], r["self_intersecting_pairs"],
                r["self_intersecting_pairs_away_from_input_ones"], r["seconds"]))
    return out


def pictures(_gen, pictures_dir):
    out = ["| mesh | | V | θmin (°) | θ̄min (°) | <30° (%) | irregular (%) | Hausdorff / diag (sampled) | seconds |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for mesh in ("fandisk", "triceratops", "cheese", "head"):
        path = os.path.join(pictures_dir, mesh + ".txt")
        with open(path, encoding="utf-8") as f:
            text = f.read()
        seconds = re.findall(r"\.\.\. ([0-9.e+-]+) s", text)   # ours, then the peer's
        def values(label):
            for line in text.splitlines():
                if line.startswith(label):
                    rest = line[len(label):].split()
                    return rest[1:3] if len(rest) >= 3 else ["", ""]   # (input, ours, peer)
            return ["", ""]
        # "Hausdorff / diagonal   -   ours (sampled, < +x)   peer (sampled, < +y)"
        haus = ["", ""]
        for line in text.splitlines():
            if line.startswith("Hausdorff / diagonal"):
                haus = re.findall(r"([0-9.e-]+) \(sampled", line)[:2] + ["", ""]
        v, a, m, s, i = (values("vertices"), values("min angle (deg)"), values("mean min angle (deg)"),
                         values("min angle < 30 deg (%)"), values("irregular vertices (%)"))
        for k, who in enumerate(("ours", "CGAL")):
            out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                mesh + (" (open)" if mesh == "head" else "") if k == 0 else "", who, v[k], a[k], m[k], s[k], i[k],
                haus[k], seconds[k] if k < len(seconds) else ""))
    return out


TABLES = {"corpus_summary": corpus_summary, "eight_models": eight_models, "pictures": pictures}


def main():
    if len(sys.argv) < 4:
        sys.stderr.write(__doc__)
        return 2
    gen, pictures_dir, files = sys.argv[1], sys.argv[2], sys.argv[3:]
    for path in files:
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        out, i = [], 0
        while i < len(lines):
            m = re.match(r"<!-- table: (\w+) -->$", lines[i].strip())
            out.append(lines[i])
            i += 1
            if not m:
                continue
            end = i
            while end < len(lines) and lines[end].strip() != "<!-- /table -->":
                end += 1
            if end == len(lines):
                sys.stderr.write("%s: table %s has no end marker\n" % (path, m.group(1)))
                return 1
            try:
                out.extend(TABLES[m.group(1)](gen, pictures_dir))
            except (OSError, KeyError, ValueError) as e:
                sys.stderr.write("%s: table %s left as it was (%s)\n" % (path, m.group(1), e))
                out.extend(lines[i:end])
            i = end
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
