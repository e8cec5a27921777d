"""Shared machinery of large campaigns: chunks flown on threads and consumed in order
(``lgw.sim.executors.map_threads``), encoded JSON written from a writer thread
(``lgw.tuning.io.write_encoded``)."""

from __future__ import annotations

import io
import threading
import time

import pytest
from lgw.sim import executors
from lgw.tuning.io import Stream, write_encoded, write_json_document


@pytest.mark.parametrize("threads", [1, 2, 3])
def test_map_threads_consumes_in_chunk_order(threads: int) -> None:
    """The early chunks are the slowest, so they finish last: the results are consumed in
    chunk order all the same, on the calling thread, every case once."""
    seen: list[tuple[int, int]] = []
    workers: set[str] = set()

    def fly(sl: slice) -> tuple[int, int]:
        workers.add(threading.current_thread().name)
        time.sleep(0.02 * max(0, 4 - sl.start // 3))
        return sl.start, sl.stop

    caller = threading.current_thread()

    def consume(r: tuple[int, int]) -> None:
        assert threading.current_thread() is caller
        seen.append(r)

    executors.map_threads(fly, 20, 3, consume, threads=threads)
    assert seen == [(a, min(a + 3, 20)) for a in range(0, 20, 3)]
    # the first chunk on the calling thread (a first call's set-up is not raced), the others
    # on the pool's threads
    assert caller.name in workers
    assert len(workers) == (1 if threads == 1 else threads + 1)


def test_map_threads_stops_on_an_error() -> None:
    flown: list[int] = []

    def fly(sl: slice) -> int:
        if sl.start == 6:
            raise ValueError("chunk 6")
        flown.append(sl.start)
        return sl.start

    with pytest.raises(ValueError, match="chunk 6"):
        executors.map_threads(fly, 1000, 2, lambda r: None, threads=2)
    assert len(flown) < 20  # the chunks not started were dropped


def _doc(texts, out) -> str:
    write_json_document({"command": "x", "cases": Stream(encoded=lambda: iter(texts)),
                         "after": 1}, out)
    return out


def test_write_encoded_to_a_file_is_the_text_written(tmp_path) -> None:
    """Through a real file (bytes from the writer thread) the document is the one written as
    text into a StringIO: the items joined by ",", in order, the keys around them in place."""
    texts = [b'{"a":1},{"a":2}', "", '{"a":3}', b'{"a":4}'] + [b'{"b":%d}' % i
                                                                 for i in range(50)]
    want = _doc(texts, io.StringIO()).getvalue()
    path = tmp_path / "doc.json"
    with open(path, "w", encoding="utf-8") as f:
        _doc(texts, f)
    assert path.read_text() == want
    assert want.startswith('{"lgw_version":') and '"cases":[{"a":1},{"a":2},{"a":3},' in want
    assert want.endswith('{"b":49}],"after":1}\n')


def test_write_encoded_raises_the_writer_error() -> None:
    """A failed write (a full disk, a closed pipe) is raised in the caller, and the producer
    does not block on the full queue."""

    class Failing(io.RawIOBase):
        def writable(self) -> bool:
            return True

        def write(self, b) -> int:
            raise OSError(28, "No space left on device")

    out = io.TextIOWrapper(io.BufferedWriter(Failing(), buffer_size=4), encoding="ascii")
    made = []

    def texts():
        for i in range(100):
            made.append(i)
            yield b"1" * 100

    with pytest.raises(OSError, match="No space left"):
        write_encoded(texts(), out)
    assert len(made) < 100  # it stopped producing after the error
