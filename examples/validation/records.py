"""A study's written results: the CSV of its figures and its Markdown table."""
import csv


def write_csv(path, columns, results):
    """One row a result (a dict), its `columns` in order (empty where a result has none);
    floats to 5 significant digits."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in results:
            values = [r.get(c, "") for c in columns]
            w.writerow([f"{v:.5g}" if isinstance(v, float) else v for v in values])


def write_table(path, header, rows):
    """A Markdown table of `header` cells over `rows` of cells (strings), also printed."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    path.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
