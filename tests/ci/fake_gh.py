#!/usr/bin/python3
"""A stand-in for GitHub's `gh` on PATH in tests/ci/check_ci.py: records each
call (arguments and the JSON it was given) in $FAKE_GH_LOG, one JSON object a
line, and keeps the pull request's comments in $FAKE_GH_STATE (a JSON list).
Understands the calls action/comment.sh makes:
  gh api --paginate repos/O/R/issues/N/comments          (list)
  gh api -X POST repos/O/R/issues/N/comments --input F   (create)
  gh api -X PATCH repos/O/R/issues/comments/ID --input F (edit)
FAKE_GH_MODE=readonly answers every call as GitHub does for a fork's
read-only token: "HTTP 403", exit 1."""
import json
import os
import re
import sys

args = sys.argv[1:]
log, state = os.environ["FAKE_GH_LOG"], os.environ["FAKE_GH_STATE"]
comments = json.load(open(state)) if os.path.exists(state) else []
body = None
if "--input" in args:
    f = args[args.index("--input") + 1]
    body = json.load(sys.stdin if f == "-" else open(f))
with open(log, "a") as out:
    out.write(json.dumps({"args": args, "input": body}) + "\n")
if os.environ.get("FAKE_GH_MODE") == "readonly":
    sys.stderr.write("gh: Resource not accessible by integration (HTTP 403)\n")
    sys.exit(1)
if args[:1] != ["api"]:
    sys.stderr.write("fake gh: only `gh api` is known\n")
    sys.exit(2)
method = args[args.index("-X") + 1] if "-X" in args else "GET"
path = [a for a in args[1:] if a.startswith("repos/")][0]
if method == "GET" and re.fullmatch(r"repos/[^/]+/[^/]+/issues/\d+/comments", path):
    # Pages of 2, as --paginate prints them: JSON arrays one after another.
    for i in range(0, max(len(comments), 1), 2):
        print(json.dumps(comments[i:i + 2]))
elif method == "POST" and re.fullmatch(r"repos/[^/]+/[^/]+/issues/\d+/comments", path):
    comments.append({"id": 1000 + len(comments), "body": body["body"], "user": {"login": "github-actions[bot]"}})
    print(json.dumps(comments[-1]))
elif method == "PATCH" and (m := re.fullmatch(r"repos/[^/]+/[^/]+/issues/comments/(\d+)", path)):
    for c in comments:
        if c["id"] == int(m.group(1)):
            c["body"] = body["body"]
            print(json.dumps(c))
            break
    else:
        sys.stderr.write("gh: Not Found (HTTP 404)\n")
        sys.exit(1)
else:
    sys.stderr.write(f"fake gh: unexpected call {args}\n")
    sys.exit(2)
json.dump(comments, open(state, "w"))
