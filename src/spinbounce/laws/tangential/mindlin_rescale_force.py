"""``tangential mindlin_rescale/force``: a Mindlin variant (:mod:`.mindlin`)."""

from .mindlin import Mindlin

LAW = Mindlin("mindlin_rescale/force")
