"""The open-water curves of the Wageningen B-screw series from their regression polynomials
(``model: propeller`` with ``open_water: {kind: b_series, ...}``; ``forces.propeller``).

Oosterveld and van Oossanen's polynomials for the series' thrust and torque coefficients at a
Reynolds number of 2 x 10^6 (no Reynolds-number correction here):

    K_T = sum C_T (J)^s (P/D)^t (A_E/A_0)^u Z^v,    K_Q = sum C_Q (J)^s (P/D)^t (A_E/A_0)^u Z^v,

39 terms for K_T and 47 for K_Q, J the advance ratio, P/D the pitch ratio (at 0.7 R), A_E/A_0
the expanded blade area ratio and Z the number of blades; valid for 0.5 <= P/D <= 1.4,
0.30 <= A_E/A_0 <= 1.05, 2 <= Z <= 7 (the series' propellers; the case's schema,
``case.ship_forces.BSeries``, holds these limits), J from 0 to where K_T vanishes. J's
powers s are 0 to 3: for one propeller, K_T and K_Q are cubics in J (``cubics``).

The coefficients are published data, transcribed here from:

- M. W. C. Oosterveld and P. van Oossanen, "Further computer-analyzed data of the Wageningen
  B-screw series", International Shipbuilding Progress 22 (251), 1975, pp. 251-262;
- as tabulated again in M. M. Bernitsas, D. Ray and P. Kinley, "K_T, K_Q and efficiency
  curves for the Wageningen B-series propellers", report 237, Department of Naval
  Architecture and Marine Engineering, University of Michigan, 1981
  (http://deepblue.lib.umich.edu/handle/2027.42/3557).

Checked: every coefficient and its four powers against two independent transcriptions (of the
1981 report, and of the 1975 paper), which agree with each other and with this table term for
term (a third had one term miscopied, 0.0010903 for 0.00110903); a B5-90 of P/D 1.0 at J =
0.83 gives K_T 0.117 and K_Q 0.0231 where the series' chart reads 0.12 and 0.023; K_T falls
with J, vanishes at J = 1.0 to 1.19 P/D, and the open-water efficiency peaks at 0.3 to 0.77
over the range (tests/test_propulsion.py).
"""

import math

import numpy as np

# (C, s, t, u, v): the coefficient of J^s (P/D)^t (A_E/A_0)^u Z^v, in the papers' order
THRUST = (
    (+0.00880496, 0, 0, 0, 0), (-0.204554, 1, 0, 0, 0), (+0.166351, 0, 1, 0, 0),
    (+0.158114, 0, 2, 0, 0), (-0.147581, 2, 0, 1, 0), (-0.481497, 1, 1, 1, 0),
    (+0.415437, 0, 2, 1, 0), (+0.0144043, 0, 0, 0, 1), (-0.0530054, 2, 0, 0, 1),
    (+0.0143481, 0, 1, 0, 1), (+0.0606826, 1, 1, 0, 1), (-0.0125894, 0, 0, 1, 1),
    (+0.0109689, 1, 0, 1, 1), (-0.133698, 0, 3, 0, 0), (+0.00638407, 0, 6, 0, 0),
    (-0.00132718, 2, 6, 0, 0), (+0.168496, 3, 0, 1, 0), (-0.0507214, 0, 0, 2, 0),
    (+0.0854559, 2, 0, 2, 0), (-0.0504475, 3, 0, 2, 0), (+0.010465, 1, 6, 2, 0),
    (-0.00648272, 2, 6, 2, 0), (-0.00841728, 0, 3, 0, 1), (+0.0168424, 1, 3, 0, 1),
    (-0.00102296, 3, 3, 0, 1), (-0.0317791, 0, 3, 1, 1), (+0.018604, 1, 0, 2, 1),
    (-0.00410798, 0, 2, 2, 1), (-0.000606848, 0, 0, 0, 2), (-0.0049819, 1, 0, 0, 2),
    (+0.0025983, 2, 0, 0, 2), (-0.000560528, 3, 0, 0, 2), (-0.00163652, 1, 2, 0, 2),
    (-0.000328787, 1, 6, 0, 2), (+0.000116502, 2, 6, 0, 2), (+0.000690904, 0, 0, 1, 2),
    (+0.00421749, 0, 3, 1, 2), (+0.0000565229, 3, 6, 1, 2), (-0.00146564, 0, 3, 2, 2),
)  # fmt: skip
TORQUE = (
    (+0.00379368, 0, 0, 0, 0), (+0.00886523, 2, 0, 0, 0), (-0.032241, 1, 1, 0, 0),
    (+0.00344778, 0, 2, 0, 0), (-0.0408811, 0, 1, 1, 0), (-0.108009, 1, 1, 1, 0),
    (-0.0885381, 2, 1, 1, 0), (+0.188561, 0, 2, 1, 0), (-0.00370871, 1, 0, 0, 1),
    (+0.00513696, 0, 1, 0, 1), (+0.0209449, 1, 1, 0, 1), (+0.00474319, 2, 1, 0, 1),
    (-0.00723408, 2, 0, 1, 1), (+0.00438388, 1, 1, 1, 1), (-0.0269403, 0, 2, 1, 1),
    (+0.0558082, 3, 0, 1, 0), (+0.0161886, 0, 3, 1, 0), (+0.00318086, 1, 3, 1, 0),
    (+0.015896, 0, 0, 2, 0), (+0.0471729, 1, 0, 2, 0), (+0.0196283, 3, 0, 2, 0),
    (-0.0502782, 0, 1, 2, 0), (-0.030055, 3, 1, 2, 0), (+0.0417122, 2, 2, 2, 0),
    (-0.0397722, 0, 3, 2, 0), (-0.00350024, 0, 6, 2, 0), (-0.0106854, 3, 0, 0, 1),
    (+0.00110903, 3, 3, 0, 1), (-0.000313912, 0, 6, 0, 1), (+0.0035985, 3, 0, 1, 1),
    (-0.00142121, 0, 6, 1, 1), (-0.00383637, 1, 0, 2, 1), (+0.0126803, 0, 2, 2, 1),
    (-0.00318278, 2, 3, 2, 1), (+0.00334268, 0, 6, 2, 1), (-0.00183491, 1, 1, 0, 2),
    (+0.000112451, 3, 2, 0, 2), (-0.0000297228, 3, 6, 0, 2), (+0.000269551, 1, 0, 1, 2),
    (+0.00083265, 2, 0, 1, 2), (+0.00155334, 0, 2, 1, 2), (+0.000302683, 0, 6, 1, 2),
    (-0.0001843, 0, 0, 2, 2), (-0.000425399, 0, 3, 2, 2), (+0.0000869243, 3, 3, 2, 2),
    (-0.0004659, 0, 6, 2, 2), (+0.0000554194, 1, 6, 2, 2),
)  # fmt: skip


def _cubic(terms, pitch_ratio: float, area_ratio: float, blades: int) -> np.ndarray:
    """The coefficients of J^0 to J^3 of one polynomial for one propeller."""
    out = np.zeros(4)
    for c, s, t, u, v in terms:
        out[s] += c * pitch_ratio**t * area_ratio**u * float(blades) ** v
    return out


def cubics(pitch_ratio: float, area_ratio: float, blades: int) -> tuple[np.ndarray, np.ndarray]:
    """K_T and K_Q of the propeller as cubics in J: the coefficients of J^0 to J^3 of each."""
    return (_cubic(THRUST, pitch_ratio, area_ratio, blades),
            _cubic(TORQUE, pitch_ratio, area_ratio, blades))  # fmt: skip


def coefficients(advance: float, pitch_ratio: float, area_ratio: float,
                 blades: int) -> tuple[float, float]:  # fmt: skip
    """K_T and K_Q at the advance ratio ``advance`` J, from every term (a check of
    ``cubics``)."""

    def total(terms):
        return sum(c * advance**s * pitch_ratio**t * area_ratio**u * float(blades) ** v
                   for c, s, t, u, v in terms)  # fmt: skip

    return total(THRUST), total(TORQUE)


def zero_thrust(thrust: np.ndarray) -> float:
    """The advance ratio where the cubic K_T (coefficients of J^0 to J^3) first vanishes
    beyond 0 (at most 2.5; the series' propellers reach it by J = 1.7)."""
    roots = np.roots(thrust[::-1])
    real = [float(r.real) for r in roots if abs(r.imag) < 1e-12 and 0.0 < r.real <= 2.5]
    return min(real) if real else 2.5


def efficiency(advance: float, thrust: float, torque: float) -> float:
    """The open-water efficiency eta_0 = J K_T / (2 pi K_Q)."""
    return advance * thrust / (2.0 * math.pi * torque)
