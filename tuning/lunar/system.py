"""Seed 001 (lunar descent, adaptive backstepping with saturation and failure) as a
``System``."""

from lgw.tuning.system import NotApplicable, laid_out_system

SYSTEM = laid_out_system(
    "lunar", "001",
    title="Adaptive backstepping for optimal descent with input saturation and failure",
    summary="lunar descent (adaptive backstepping)",
    bounds="the (18) constants beside the true filter L2 gains, and (19)-(21) for a case",
    simulate="fly the Section 5 scenario (or random cases): errors, thrust, torque, d0e, V2",
    verify="property campaign: V2 (13), (18), (19), (21a) against measured runs",
    report="the derivation report (Markdown, LaTeX, HTML) with every claim's verdict",
    tune="gains, command filter and thrust redundancy for a tracking target and the thrust "
         "limit with the failure, certified",
    compare="Section 5 with and without failure and saturation, ideal against coupled "
            "pointing, the filter swept",
    optimal=NotApplicable(
        "seed 001 has no separate offline baseline: its law tracks the paper's own "
        "optimal descent (linear-tangent steering (3)-(4), solved as a boundary-value "
        "problem), which simulate and compare fly; the lossless-convexification baseline is "
        "seed 000's Part 1 comparison"),
)
