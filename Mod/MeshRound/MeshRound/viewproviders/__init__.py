"""View provider proxies (GUI only).  Their module paths are stored in .FCStd files: do not move them."""
