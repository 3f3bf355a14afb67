"""The paper's Figures 3-10: which runs, times and views each shows (filled in below)."""


def make_all(args, runs, finished):
    return []
