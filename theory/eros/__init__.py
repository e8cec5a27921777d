"""lgw.theory.eros: seed 002 (fuzzy fast terminal sliding mode landing on 433 Eros) derived
and checked: surfaces, settling and reaching times, the control (11)-(19), the fuzzy blend
(20)-(22), the cubic reference (8)-(10), the two-mass-point gravity (2), claims and coverage."""
