"""Code clauses: ASCE/SEI 7-22 (asce7_22) and EN 15129 / EN 1998 (en15129)."""
