"""``tangential mindlin_rescale``: a Mindlin variant (:mod:`.mindlin`)."""

from .mindlin import Mindlin

LAW = Mindlin("mindlin_rescale")
