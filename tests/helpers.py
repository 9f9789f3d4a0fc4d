"""Small builders of cases for the tests."""

import copy

import seacable


def chain_case(n=20, top=None, bottom=None, initial=None, simulation=None, environment=None,
               **cable):  # fmt: skip
    """A case dict for one planar cable of 10 m (1 kg/m) with overridable parts."""
    data = {
        "name": f"test chain {n}",
        "environment": environment or {"in_air": True},
        "cables": [
            {
                "links": n,
                "length": 10.0,
                "diameter": 0.01,
                "mass_per_length": 1.0,
                "top": top or {"type": "fixed"},
                "bottom": bottom or {"type": "free"},
                "initial": initial or {"shape": "arc", "top_angle_deg": 0.0},
                **cable,
            }
        ],
        "simulation": simulation or {"duration": 1.0, "output_interval": 0.1},
    }
    return copy.deepcopy(data)


def run(data, **kwargs):
    return seacable.simulate(seacable.load_case(data), **kwargs)
