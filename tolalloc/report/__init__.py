"""Tolerance tables (CSV / Markdown / LaTeX) and figures drawn from result objects."""

