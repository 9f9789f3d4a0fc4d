"""The page of output variables: every variable a run can write, by the part that writes it,
from ``seacable.system.variables.catalogue`` (the declarations the results are written from).
docs/conf.py writes it as docs/reference/outputs.md at each build."""

from seacable.system.variables import catalogue

INTRO = """\
# Output variables

A run's results file (NetCDF) opens in xarray as a DataTree: the system's energies at the top,
a group `bodies/<name>` per body and `lines/<name>` per line, each variable over `time` (and
`segment` or `node` along a line). Every variable carries its `units` and `long_name`
attributes, as listed here. Units are SI; angles of bodies are in degrees.

Signs and ends, in short ({doc}`../conventions` has them in full):

- A line runs from its `from` point to its `to` point. Node 0 is at `from`; segment k joins
  node k to node k + 1; `arc_length` is measured from `from`.
- `tension` is the axial force, positive when the line pulls. A lumped-mass line's is each
  segment's tension (never negative); a rigid line's is the axial force at each segment's
  centre (negative when pushed); a tie's is zero when slack. The tension at a fairlead is
  the last segment's (index -1) when the line ends there (`to`), the first's (index 0) when it
  starts there.
- `from_force_*` and `to_force_*` are the forces the line applies to its end points, in the
  earth frame: its end node's loads less that node's inertia, so at a fixed anchor the anchor
  load, and at a moving body what the body feels. The force a vessel must apply to hold the
  line is their opposite.
- A body's `line_force_*` and `line_moment_*` sum what its lines, ties and joints apply to it,
  the moment about its reference point.
- `position_*`, `velocity_*` are those of the body's reference point in the earth frame;
  `roll`, `pitch`, `yaw` are its orientation, R = Rz(yaw) Ry(pitch) Rx(roll).

The attributes of the file keep the case, every setting resolved, the software's versions and
the run's status (`complete`, `diverged`, `interrupted`).
"""


def outputs_md() -> str:
    out = [INTRO]
    for what, group, variables in catalogue():
        out += [f"## {what[0].upper()}{what[1:]}", "", f"In `{group}`:", ""]
        out += ["| variable | over | unit | meaning |", "| --- | --- | --- | --- |"]
        for name, (dims, unit, meaning) in variables.items():
            over = " × ".join(dims)
            out.append(f"| `{name}` | {over} | {'-' if unit == '1' else unit} | {meaning} |")
        out.append("")
    return "\n".join(out) + "\n"
