"""Document object proxies.  Their module paths are stored in .FCStd files: do not move or rename."""
