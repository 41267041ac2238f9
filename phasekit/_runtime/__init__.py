"""Runtime plumbing (private): argument validation, errors and statuses, Ctrl-C, worker pools,
wall budgets and progress, and the CasADi-to-heyoka translation. The lowest layer: it imports
nothing else from phasekit (see docs/architecture.md)."""
