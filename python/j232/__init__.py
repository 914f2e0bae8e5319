"""j232: Monte Carlo assessment of the SAE J232 thrown-object test of rotary mowers.

    import j232
    s = j232.Scenario("scenarios/highway-pivoted.toml")
    r = s.assess(replicates=200, seed=1)
    r["verdict"], r["pass_probability"], r["criteria"]      # as result.json holds them
    r["marks_table"]["x"], r["histograms"]["exit_speed_m_s"]["counts"]   # NumPy arrays

    faster = s.with_settings({"blade_speed": "3000 rpm"})  # a sweep point
    j232.impact("scenarios/impact/highway-pivoted.toml", {"restitution": 0.5})

Bad input raises j232.InputError (a ValueError) naming the file, key, value and what was
expected. The simulation releases the GIL, so threads of a Python program can run
assessments side by side. docs/python.md has the whole interface and an example.
"""
from ._j232 import InputError, FileError, Scenario, impact, __version__, git_revision

__all__ = ["Scenario", "impact", "sweep_point", "InputError", "FileError", "__version__", "git_revision"]


def sweep_point(scenario, settings, replicates=None, seed=None, threads=0, marks=False):
    """One point of a sweep: `scenario` (a Scenario, a path or a dict) with `settings` on top,
    assessed with common random numbers (the same seed at every point), as `j232 sweep` does."""
    if not isinstance(scenario, Scenario):
        scenario = Scenario(scenario)
    return scenario.with_settings(settings).assess(replicates=replicates, seed=seed, threads=threads, marks=marks)
