"""lgw.theory.mars: seed 000 (Mars powered descent, fixed-time multiple sliding surfaces).

* ``parameters``     the paper's constants (Table I, III) and the values it leaves out, sourced;
* ``gains``          the gain set (frozen), its validation and the TOML loader;
* ``mss``            the sliding surfaces (15), (21) and the laws (25) printed and corrected;
* ``supertwisting``  the super-twisting baseline (46);
* ``bounds``         every settling-time and neighbourhood bound as a function of the gains;
* ``reduced``        the per-axis closed loop for reference trajectories;
* ``claims``         every claim of the paper, derived and judged.
"""
