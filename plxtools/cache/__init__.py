"""plx's one cache layer: every cached answer, one key rule, one store.

- `folder`: where the cache lives, and whether it may be trusted (private to the user);
- `store`: entries authenticated with a per-user secret kept outside the cache folder, written
  atomically, pruned least recently used first under a size cap;
- `reads`: what a computation really read (files by content, probes that found nothing, folder
  listings, environment variables), recorded by the code that read it and checked again before an
  entry is believed;
- `stamp`: plxtools' own code, as a digest of its source files' contents.

This package sits below every other layer and imports nothing of plxtools: a replayed run
(`plxtools.runmemo`) loads only these modules.
"""
