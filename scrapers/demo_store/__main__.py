"""``python -m scrapers.demo_store [--port 8765] [--host 127.0.0.1] [--crawl-delay 0.25] [--slow-s 3]``"""

from __future__ import annotations

import argparse
import sys

from scrapers.demo_store.server import DemoStore


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m scrapers.demo_store", description=__doc__)
    parser.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1)")
    parser.add_argument("--port", type=int, default=8765, help="port (0 picks a free one; default 8765)")
    parser.add_argument("--crawl-delay", type=float, default=0.25, help="Crawl-delay in robots.txt (s)")
    parser.add_argument("--slow-s", type=float, default=3.0, help="how long the slow page takes (s)")
    args = parser.parse_args(argv)
    store = DemoStore(args.host, args.port, crawl_delay=args.crawl_delay, slow_s=args.slow_s).start()
    print(
        f"demo store serving {len(store.product_pages())} product pages at {store.base_url}/ "
        f"(sitemap {store.base_url}/sitemap.xml); Ctrl-C stops",
        file=sys.stderr,
        flush=True,
    )
    print(store.base_url, flush=True)
    store.serve_forever()


if __name__ == "__main__":
    main()
