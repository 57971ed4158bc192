# SPDX-License-Identifier: Apache-2.0
"""Render farms on Dask (or Ray): a render's passes in chunks, rendered as tasks anywhere,
merged exactly into one image.

The render runs in a pass-independent mode ("pppm" by default, or "vcm", "bpt", "vm"): pass
``i`` depends only on the scene,
the settings and ``i``, and the merge of partial renders is exact (see
:class:`libppm.Partial`), so the image of ``passes`` passes is the same bits as one process
rendering them, however the chunks were split, ordered, retried or resumed.

>>> from dask.distributed import Client
>>> image = libppm.distributed.render("scene.json", passes=256, chunk_passes=8,
...                                   client=Client("scheduler:8786"), output="image.exr",
...                                   checkpoint="image.ppmpart", photons_per_pass=200000)

Each task loads the scene file on its worker (once per worker process: later tasks reuse it),
renders its chunk and returns the partial's bytes; the driver merges them as they arrive,
rewrites ``output`` and ``checkpoint`` atomically once per round (after merging every chunk
that has arrived), and shows a progress bar.
A driver started again with the same ``checkpoint`` renders only the passes it lacks. The
engine retries a failed task or a lost worker's task (``retries`` times); a retried chunk
renders the same bits. The scene path must name the same file on every worker (a shared
file system, or the same path on each machine).
"""
from __future__ import annotations

import importlib
import os
import time
from typing import (TYPE_CHECKING, Any, Callable, Dict, Iterable, Iterator, List, Mapping,
                    Optional, Sequence, Tuple)

from ._typing import Float32Array, PathLike
from .partial import Partial, check_image_path, write_image

if TYPE_CHECKING:
    from .scene_file import SceneFile

__all__ = ["render", "render_chunk"]

# Scene files loaded by this worker process: (path, mtime, size, threads) -> SceneFile.
_scene_cache: Dict[Tuple[str, int, int, int], SceneFile] = {}


def _scene_file(path: str, threads: int) -> SceneFile:
    from .context import Context
    from .scene_file import load
    status = os.stat(path)
    key = (path, status.st_mtime_ns, status.st_size, threads)
    scene_file = _scene_cache.get(key)
    if scene_file is None:
        for old in [k for k in _scene_cache if k[0] == path]:
            _scene_cache.pop(old).close()
        context = Context(threads=threads) if threads else None
        scene_file = _scene_cache[key] = load(path, context)
    return scene_file


# The modes whose passes stand alone, so that partial renders of them merge exactly.
PASS_INDEPENDENT_MODES = ("pppm", "vcm", "bpt", "vm")


def render_chunk(scene_path: PathLike, first: int, end: int, settings: Mapping[str, Any],
                 pass_total: int = 0, threads: int = 0) -> bytes:
    """Renders passes ``first .. end-1`` of the scene with ``settings`` (a dict of render
    settings; mode "pppm" unless it names another pass-independent one) on ``threads`` threads (0: all cores) and returns the partial
    render's bytes (a task's work; also usable on its own). The scene file is loaded once
    per process."""
    scene_file = _scene_file(os.fspath(scene_path), int(threads))
    settings = dict(settings)
    renderer = scene_file.create_renderer(mode=settings.pop("mode", "pppm"), **settings)
    try:
        for index in range(int(first), int(end)):
            renderer.render_pass_index(index)
        partial = renderer.partial()
        partial.pass_total = pass_total
        return partial.to_bytes()
    finally:
        renderer.close()


class _DaskBackend:
    def __init__(self, client: Any, retries: int) -> None:
        self.client, self.retries = client, retries

    def submit(self, *args: Any) -> Any:
        return self.client.submit(render_chunk, *args, retries=self.retries, pure=False)

    def completed(self, futures: List[Any]) -> Iterator[List[Tuple[Any, bytes]]]:
        # Imported by name: the optional dependencies need not ship type information.
        as_completed = importlib.import_module("dask.distributed").as_completed
        for batch in as_completed(futures, with_results=True).batches():
            yield batch

    def cancel(self, futures: Iterable[Any]) -> None:
        self.client.cancel(list(futures))


class _RayBackend:
    def __init__(self, retries: int) -> None:
        import ray
        self.ray = ray
        if not ray.is_initialized():
            ray.init()
        self.task = ray.remote(max_retries=retries, retry_exceptions=True)(render_chunk)

    def submit(self, *args: Any) -> Any:
        return self.task.remote(*args)

    def completed(self, futures: List[Any]) -> Iterator[List[Tuple[Any, bytes]]]:
        pending = list(futures)
        while pending:
            done, pending = self.ray.wait(pending, num_returns=1)
            if pending:  # and whatever else is ready now
                more, pending = self.ray.wait(pending, num_returns=len(pending), timeout=0)
                done += more
            yield [(future, self.ray.get(future)) for future in done]

    def cancel(self, futures: Iterable[Any]) -> None:
        for future in futures:
            self.ray.cancel(future)


def _chunks(missing: Iterable[Tuple[int, int]], chunk_passes: int) -> Iterator[Tuple[int, int]]:
    for first, end in missing:
        for start in range(first, end, chunk_passes):
            yield start, min(start + chunk_passes, end)


def _write(merged: Partial, output: Optional[str], checkpoint: Optional[str],
           layers: Sequence[str]) -> None:
    if checkpoint is not None:
        merged.save(checkpoint)
    if output is not None:
        write_image(output, merged.image(), {name: merged.layer(name) for name in layers})


def render(scene_path: PathLike, passes: int, chunk_passes: Optional[int] = None,
           client: Any = None, ray: bool = False, output: Optional[PathLike] = None,
           checkpoint: Optional[PathLike] = None, progress: bool = True,
           layers: Sequence[str] = (), retries: int = 3,
           callback: Optional[Callable[[Partial, Tuple[int, int]], Optional[bool]]] = None,
           threads_per_task: int = 0, **settings: Any) -> Float32Array:
    """Renders ``passes`` passes of a scene file on a Dask cluster (``client``, a
    ``dask.distributed.Client``) or on Ray (``ray=True``; connects to a running cluster, or
    starts a local one) and returns the image: float32 ``(H, W, 3)`` linear radiance.

    ``chunk_passes``: passes per task (default: ``passes`` split into about 4 chunks per
    worker, at least 1 pass each). ``output``: the image path, rewritten atomically after
    each round of merges (EXR linear float with ``layers``, e.g. ``("radius", "photons")``;
    PNG or JPEG sRGB). ``checkpoint``: a partial-render file holding the merged passes,
    rewritten with the image; an existing one is resumed. ``progress``: a tqdm progress bar
    (if tqdm is installed). ``retries``: how often the engine retries a failed chunk.
    ``callback``: called as ``callback(partial, (first, end))`` after each chunk's merge;
    returning ``False`` stops (the checkpoint keeps the passes merged so far).
    ``threads_per_task``: libppm's threads in each task (0: all cores of the worker; 1 suits
    a worker per core). Keyword ``settings`` override the scene's integrator settings (``photons_per_pass=20000``, ``seed=3``, ...); the mode
    (``mode=``) must be pass-independent: "pppm" (the default), "vcm", "bpt" or "vm".
    """
    scene_path = os.path.abspath(os.fspath(scene_path))
    passes = int(passes)
    if passes < 1:
        raise ValueError(f"passes must be at least 1, not {passes}")
    if (client is None) == (not ray):
        raise ValueError("give either client=<dask.distributed.Client> or ray=True")
    if settings.get("mode", "pppm") not in PASS_INDEPENDENT_MODES:
        raise ValueError("distributed renders need a pass-independent mode (" + ", ".join(PASS_INDEPENDENT_MODES) +
                         f"), not {settings['mode']!r}")
    for name in layers:
        if name not in ("radius", "photons"):
            raise ValueError(f"unknown layer {name!r} (layers: radius, photons)")
    if output is not None:
        output = os.fspath(output)
        check_image_path(output)
    checkpoint = None if checkpoint is None else os.fspath(checkpoint)
    if not os.path.isfile(scene_path):
        raise FileNotFoundError(f"{scene_path}: no such scene file")

    backend = _DaskBackend(client, retries) if client is not None else _RayBackend(retries)
    if chunk_passes is None:
        if isinstance(backend, _DaskBackend):
            workers = len(client.scheduler_info()["workers"])
        else:
            workers = max(1, int(backend.ray.cluster_resources().get("CPU", 1)))
        chunk_passes = max(1, passes // (4 * max(1, workers)))
    chunk_passes = int(chunk_passes)
    if chunk_passes < 1:
        raise ValueError(f"chunk_passes must be at least 1, not {chunk_passes}")

    merged = None
    if checkpoint is not None and os.path.exists(checkpoint):
        merged = Partial.load(checkpoint)
    missing = merged.missing(passes) if merged is not None else [(0, passes)]
    chunks = list(_chunks(missing, chunk_passes))

    bar = None
    if progress:
        try:
            tqdm = importlib.import_module("tqdm.auto").tqdm
            bar = tqdm(total=passes, initial=passes - sum(e - f for f, e in missing), unit="pass",
                       desc=os.path.basename(scene_path))
        except ImportError:
            bar = None

    futures = {backend.submit(scene_path, first, end, dict(settings), passes,
                              int(threads_per_task)): (first, end)
               for first, end in chunks}
    started = time.perf_counter()
    try:
        # Each round merges every chunk that has arrived, then rewrites the image and the
        # checkpoint once: the writes cost the driver per round, not per chunk.
        stop = False
        for batch in backend.completed(list(futures)):
            for future, data in batch:
                chunk = futures.pop(future)
                part = Partial.from_bytes(data)
                if merged is None:
                    merged = part
                else:
                    merged.merge(part)
                    part.close()
                merged.pass_total = passes
                if bar is not None:
                    bar.update(chunk[1] - chunk[0])
                if callback is not None and callback(merged, chunk) is False:
                    stop = True
                    break
            assert merged is not None  # a round holds at least one chunk
            _write(merged, output, checkpoint, layers)
            if stop:
                break
    finally:
        if futures:
            backend.cancel(futures)
        if bar is not None:
            bar.close()
    if merged is None:
        raise RuntimeError("no pass was rendered")
    merged.elapsed = time.perf_counter() - started
    return merged.image()
