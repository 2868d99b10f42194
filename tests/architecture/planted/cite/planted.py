# Section marks planted for tests/architecture (never run).
# Case 1 of paper 000 (§5.1.1) names its paper: fine.
# The exit codes of §18.10.
