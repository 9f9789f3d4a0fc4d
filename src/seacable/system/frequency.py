"""The fastest natural frequency of a system: what limits an explicit step (the rk4 step's
warning, the statics' dynamic relaxation)."""

import numpy as np

from seacable.system.assemble import BuiltSystem


def fastest_frequency(system: BuiltSystem) -> tuple[float, str]:
    """Estimate of the fastest motion [rad/s] and what sets it: the fastest axial mode of any
    lumped segment between two nodes, 2 sqrt(EA / (m l)), and the zigzag mode of any rigid
    segment, turning about its centre against its two joint springs and the tension,
    omega^2 = (2 (k_i + k_i+1) + T l_i) / J_i, T bounded by the rigid lines' apparent weight and
    the weight of the bodies they carry. Bodies' own springs are not counted yet."""
    p = system.params
    best, what = 0.0, ""
    for li, line in enumerate(system.layout.lines):
        n, s0, c0 = int(p.line_n[li]), int(p.line_seg[li]), int(p.line_node[li])
        mass = np.minimum(p.node_mass[c0 : c0 + n], p.node_mass[c0 + 1 : c0 + n + 1])
        mass = mass + 0.5 * p.seg_added_mass[s0 : s0 + n]
        omega = 2.0 * np.sqrt(p.seg_stiffness[s0 : s0 + n] / (mass * p.seg_length[s0 : s0 + n]))
        i = int(np.argmax(omega))
        if omega[i] > best:
            best = float(omega[i])
            what = f"axial waves on segment {i} of line '{line}' ({p.seg_length[s0 + i]:.3g} m)"
    segments = int(p.rs_n.sum()) if len(p.rs_n) else 0
    carried = p.rs_tip[p.rs_tip >= 0] if len(p.rs_n) else np.zeros(0, dtype=np.int64)
    tension = float(np.abs(p.rs_wet_weight[:segments]).sum())
    tension += float(p.gravity * p.body_mass[carried].sum())  # the bodies hanging on them
    for li in range(len(p.rs_n)):
        n, s0 = int(p.rs_n[li]), int(p.rs_seg[li])
        k = p.rs_joint_stiffness[s0 : s0 + n]
        length = p.rs_length[s0 : s0 + n]
        omega = np.sqrt((2.0 * (k + np.append(k[1:], 0.0)) + tension * length)
                        / p.rs_inertia[s0 : s0 + n])  # fmt: skip
        i = int(np.argmax(omega))
        if omega[i] > best:
            best = float(omega[i])
            what = (f"zigzag of segment {i} of line '{system.layout.rigid[li]}' "
                    f"({length[i]:.3g} m, joint springs and tension)")  # fmt: skip
    return (best, what) if best > 0.0 else (1.0, "no line")
