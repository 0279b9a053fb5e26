"""report.py's shared parts: the repository and the messages on stderr."""
import os
import sys


REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def loud(msg):
    log("!" * 78 + "\n!! " + msg + "\n" + "!" * 78)
