//! Explicit asperity-by-asperity solver (in progress).
