from rapidgen.entry import main

raise SystemExit(main())
