"""paper_disk.py's estimate of a finished run's disk on made-up sizes: outputs from the input's
maxTime and outputInterval times the particles and the late outputs' bytes per particle, the
history from the quick run's rows after the first, the checkpoints the input keeps."""

import os
import sys
import tempfile
import unittest

sys.path.insert(
    0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "StandAlone", "Studies")
)
import paper_disk  # noqa: E402


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)


class EstimateTest(unittest.TestCase):
    def test_estimate_from_measured_sizes(self):
        with tempfile.TemporaryDirectory() as root:
            # A carried run whose first output is small and whose later ones are 50 and 80 bytes
            # a particle: the late outputs' largest, 80, counts.
            head = b'<VTKFile><Piece NumberOfPoints="10">'
            for step, size in ((0, 100), (5, 500), (9, 800)):
                write(
                    os.path.join(root, "carry", "R", "particles", "step_%06d.vtu" % step),
                    head + b" " * (size - len(head)),
                )
            self.assertEqual(paper_disk.output_bytes_per_particle(os.path.join(root, "carry")), 80)
            # The quick run of Flux_1e-9: a header, a first row, then rows of 9 and 19 bytes and
            # newlines: 15 bytes a row; two checkpoints, the larger 1000 bytes.
            quick = os.path.join(root, "quick")
            write(
                os.path.join(quick, "Flux_1e-9", "history.csv"),
                b"step,t\n0,0\n" + b"x" * 9 + b"\n" + b"y" * 19 + b"\n",
            )
            write(os.path.join(quick, "Flux_1e-9", "checkpoints", "a.ckpt"), b"0" * 1000)
            write(os.path.join(quick, "Flux_1e-9", "checkpoints", "b.ckpt"), b"0" * 10)
            outputs, kept = paper_disk.outputs_of("Flux_1e-9")
            self.assertEqual((outputs, kept), (51, 2))  # 100 s every 2 s, 0 included; cycle 2
            self.assertEqual(
                paper_disk.estimate("Flux_1e-9", 1000, 10, 80, quick),
                (51 * 10 * 80, 1000 * 15, 2 * 1000),
            )


if __name__ == "__main__":
    unittest.main()
