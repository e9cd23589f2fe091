"""A study's written results: the CSV of its figures and its Markdown table."""
import csv


def write_csv(path, columns, results, comments=()):
    """One row a result (a dict), its `columns` in order (empty where a result has none);
    floats to 5 significant digits; after `comments`, lines that open with "# "."""
    with open(path, "w", newline="") as f:
        f.writelines(f"# {line}\n" for line in comments)
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


def plot_forces(path, curves, title, time_label, drag_limits=None):
    """Drag and lift coefficients against time, one (label, t, C_D, C_L) a curve, into
    `path` (PNG)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 1, figsize=(8, 5), sharex=True)
    for label, t, cd, cl in curves:
        axes[0].plot(t, cd, lw=0.8, label=label)
        axes[1].plot(t, cl, lw=0.8, label=label)
    axes[0].set_ylabel("C_D")
    if drag_limits:
        axes[0].set_ylim(*drag_limits)
    axes[1].set_ylabel("C_L")
    axes[1].set_xlabel(time_label)
    axes[0].legend(fontsize=7, ncol=2)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def pressure_field(ax, x, p, fluid, vmax, xlim, ylim, title):
    """Particles on `ax`: the `fluid` ones (a mask) coloured by `p` from 0 to `vmax`,
    the walls grey; returns the fluid's scatter (for a colour bar)."""
    drawn = ax.scatter(x[fluid, 0], x[fluid, 1], c=p[fluid], s=1.5, cmap="viridis", vmin=0,
                       vmax=vmax)
    ax.scatter(x[~fluid, 0], x[~fluid, 1], c="0.55", s=1)
    ax.set_aspect("equal")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_title(title)
    return drawn
