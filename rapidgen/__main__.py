from rapidgen.cli import main

raise SystemExit(main())
