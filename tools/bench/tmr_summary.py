"""Figures from tmr_reconstruct's output, for the benchmark scripts (their
form is ReconstructImagesSummary's in reconstruct_images.cc)."""
import re


def first_number(pattern, text):
    """The first group of `pattern` in `text` as a number, NaN if absent."""
    match = re.search(pattern, text)
    return float(match.group(1)) if match else float("nan")


def stage_seconds(summary):
    """(extraction, matching) seconds from a summary.txt."""
    return (first_number(r"with features: \d+ \(([0-9.]+) s\)", summary),
            first_number(r"matching[:,] .*?([0-9.]+) s\)", summary))
