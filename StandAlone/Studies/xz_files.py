"""Files xz-compressed for the carry (paper_carry.py, figure_carry.py) and back."""
import lzma
import shutil


def compress(source, target, preset):
    """Writes `source` to `target` (its name ending in .xz) compressed at `preset`."""
    with open(source, "rb") as src, lzma.open(target, "wb", preset=preset) as dst:
        shutil.copyfileobj(src, dst)


def decompress(source, target):
    """Writes the .xz file `source` to `target` as it was."""
    with lzma.open(source, "rb") as src, open(target, "wb") as dst:
        shutil.copyfileobj(src, dst)
