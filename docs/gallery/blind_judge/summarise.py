"""Summarise a blind judge's scores: python summarise.py judge_output.json

judge_output.json: a list of {"image": path, "match_score": int, "differences": [...],
"suggestions": [...]} (or a dict image -> that object). Prints mean, per-source means and the
five worst, using judge_key.json (image file name -> prompt id and source)."""
import json, os, statistics, sys
from collections import defaultdict

here = os.path.dirname(os.path.abspath(__file__))
key = json.load(open(os.path.join(here, "judge_key.json")))
out = json.load(open(sys.argv[1]))
items = out if isinstance(out, list) else [dict(v, image=k) for k, v in out.items()]
scores = {os.path.basename(it["image"]): it for it in items}
by_source = defaultdict(list)
for name, it in scores.items():
    by_source[key[name]["source"]].append(it["match_score"])
allv = [it["match_score"] for it in scores.values()]
print(f"n={len(allv)} mean={statistics.mean(allv):.1f}")
for src, v in sorted(by_source.items()):
    print(f"  {src:16s} n={len(v):2d} mean={statistics.mean(v):.1f}")
for name, it in sorted(scores.items(), key=lambda kv: kv[1]["match_score"])[:5]:
    print(f"  worst {it['match_score']:3d} {key[name]['id']}: {'; '.join(it.get('differences', [])[:2])}")
